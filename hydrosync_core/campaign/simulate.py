"""A simulated campaign: one project per survey day filled by the analyses' demo simulators.

Used by the tests, ``benchmarks/bench_campaign.py`` and anyone who wants to try
``hydrosync batch`` without data::

    python -m hydrosync_core.campaign.simulate OUT_DIR --days 4 --analyses latency tilt_alignment
    hydrosync batch OUT_DIR/campaign.toml
"""

from __future__ import annotations

import argparse
import datetime as _dt
from pathlib import Path

from hydrosync_core.project import Project, default_vessel


def make_campaign(folder: str | Path, days: int = 4,
                  analyses: tuple[str, ...] = ("latency", "tilt_alignment"), seed: int = 1,
                  start: str = "2024-06-03", report: bool = False,
                  params: dict[str, dict] | None = None) -> Path:
    """Write ``days/<date>.h5`` (one per day) and ``campaign.toml`` in *folder*.

    Each project holds the demo data of every analysis in *analyses* (seed ``seed + day``);
    the campaign runs those analyses with *params* (default: the schemas' defaults).
    Returns the campaign file.
    """
    from hydrosync_core.plugins import get_spec
    from hydrosync_core.plugins.spec import load_object

    folder = Path(folder)
    (folder / "days").mkdir(parents=True, exist_ok=True)
    first = _dt.date.fromisoformat(start)
    specs = [get_spec(a) for a in analyses]
    for day in range(days):
        date = first + _dt.timedelta(days=day)
        project = Project.new(f"survey day {date}", vessel=dict(default_vessel(),
                                                                name="simulated launch"))
        for spec in specs:
            load_object(spec.demo)(project, seed=seed + day)
        project.save(folder / "days" / f"{date}.h5")
        project.close()
    lines = ["[campaign]", f'name = "Simulated campaign ({days} days)"', "",
             "[projects]", 'glob = "days/*.h5"', ""]
    for spec in specs:
        lines.append(f"[analyses.{spec.id}]")
        for key, value in (params or {}).get(spec.id, {}).items():
            lines.append(f"{key} = {_toml_value(value)}")
        lines.append("")
    lines += ["[outputs]", 'dir = "output"', f"report = {str(report).lower()}",
              "summary = true", ""]
    path = folder / "campaign.toml"
    path.write_text("\n".join(lines), encoding="utf-8")
    return path


def _toml_value(value) -> str:
    if isinstance(value, bool):
        return str(value).lower()
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(value, list | tuple):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    return repr(value)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description="Write a simulated campaign.")
    parser.add_argument("folder")
    parser.add_argument("--days", type=int, default=4)
    parser.add_argument("--analyses", nargs="+", default=["latency", "tilt_alignment"])
    parser.add_argument("--report", action="store_true", help="ask for a PDF per project")
    args = parser.parse_args(argv)
    path = make_campaign(args.folder, args.days, tuple(args.analyses), report=args.report)
    print(path)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
