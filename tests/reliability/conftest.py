"""Fault cases of issue #9 ("Nothing lost, ever"): the ``reliability`` marker and helpers.

Every test here is marked ``reliability`` (run only these with ``pytest -m reliability``)
and runs inside the normal ``pytest -q`` / ``make test``. Tests that inject faults record
each case in the session's fault table, printed at the end of the run as
"cases tried / clean / failed by kind" (the table of the issue's closing note).
Set ``HYDROSYNC_FAULT_SCALE=10`` to multiply the number of random cases.
"""

from __future__ import annotations

import importlib.util
import os
import re
import subprocess
import sys
import time
from collections import defaultdict
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
SCALE = max(1, int(os.environ.get("HYDROSYNC_FAULT_SCALE", "1")))

_TABLE: dict[str, list[int]] = defaultdict(lambda: [0, 0])
_FAILURES: list[str] = []


def pytest_collection_modifyitems(config, items):
    here = Path(__file__).parent
    for item in items:
        if here in Path(str(item.fspath)).parents:
            item.add_marker(pytest.mark.reliability)


def pytest_terminal_summary(terminalreporter, exitstatus, config):
    if not _TABLE:
        return
    tr = terminalreporter
    tr.section("issues #9 and #28 fault cases")
    tr.write_line(f"{'kind':<46} {'tried':>6} {'clean':>6} {'failed':>7}")
    for kind in sorted(_TABLE):
        tried, clean = _TABLE[kind]
        tr.write_line(f"{kind:<46} {tried:>6} {clean:>6} {tried - clean:>7}")
    total = [sum(v[0] for v in _TABLE.values()), sum(v[1] for v in _TABLE.values())]
    tr.write_line(f"{'total':<46} {total[0]:>6} {total[1]:>6} {total[0] - total[1]:>7}")
    for failure in _FAILURES[:20]:
        tr.write_line(f"  failed: {failure}")


class FaultTable:
    """Count a fault case as clean (every check held) or failed, by kind."""

    def record(self, kind: str, clean: bool, detail: str = "") -> bool:
        _TABLE[kind][0] += 1
        _TABLE[kind][1] += bool(clean)
        if not clean:
            _FAILURES.append(f"{kind}: {detail}")
        return clean


@pytest.fixture(scope="session")
def faults() -> FaultTable:
    return FaultTable()


def load_script(name: str):
    """Import ``scripts/<name>.py`` (the corpus builders) as a module."""
    path = ROOT / "scripts" / f"{name}.py"
    spec = importlib.util.spec_from_file_location(f"hydrosync_script_{name}", path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


def cli_command() -> list[str]:
    """How to start ``hydrosync`` as a separate process (the console script if installed)."""
    script = Path(sys.executable).with_name("hydrosync")
    if script.exists():
        return [str(script)]
    return [sys.executable, "-m", "hydrosync_core.cli"]


def cli_env() -> dict:
    env = dict(os.environ)
    env.pop("HYDROSYNC_DEBUG", None)
    env["PYTHONPATH"] = str(ROOT) + os.pathsep + env.get("PYTHONPATH", "")
    env["OPENBLAS_NUM_THREADS"] = "1"
    return env


def run_cli(*args, timeout: float = 60.0, **kwargs) -> subprocess.CompletedProcess:
    return subprocess.run([*cli_command(), *map(str, args)], capture_output=True, text=True,
                          timeout=timeout, env=cli_env(), **kwargs)


def start_cli(*args, **kwargs) -> subprocess.Popen:
    return subprocess.Popen([*cli_command(), *map(str, args)], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, env=cli_env(), **kwargs)


_PROGRESS_LINE = re.compile(r"^\[\s*\d+(\.\d+)?%\] ")


def digest(path: Path) -> str:
    """SHA-256 of a file: "the project is byte-identical" after a refused command."""
    import hashlib

    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


@pytest.fixture
def project(tmp_path) -> Path:
    """A new empty project file."""
    from hydrosync_core.project import Project

    path = tmp_path / "P.h5"
    Project.new("P").save(path)
    return path


def stderr_lines(text: str) -> list[str]:
    """The message lines of *text*: progress lines (``[ 42.0%] …``, printed every 5 s
    when a command runs long, as on a loaded machine) are not messages."""
    return [line for line in text.splitlines()
            if line.strip() and not _PROGRESS_LINE.match(line)]


def temporaries(folder: Path, name: str) -> list[Path]:
    """HydroSync temporaries of *name* in *folder* (new and legacy names)."""
    return sorted(p for p in folder.iterdir()
                  if p.name.startswith(f".{name}.") and p.name.endswith(".tmp")
                  or p.name == f"{name}.tmp")


def wait_for(predicate, timeout: float = 10.0, step: float = 0.0005) -> bool:
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        if predicate():
            return True
        time.sleep(step)
    return False


def make_big_project(path: Path, megabytes: float = 64.0) -> Path:
    """A HydroSync project of about *megabytes* MB (random, incompressible arrays)."""
    from hydrosync_core.project import Project
    from hydrosync_core.project.vessel import set_sensor

    rng = np.random.default_rng(7)
    project = Project.new("big")
    n = int(megabytes * 1e6 * 0.7 / 24)
    m = int(megabytes * 1e6 * 0.3 / 32)
    project.put("raw/pool/lidar", rng.normal(size=(n, 3)))
    project.put_table("raw/pool/mbes", {c: rng.normal(size=m) for c in ("time", "x", "y", "z")})
    set_sensor(project, "motion", [0.0, 0.0, 0.0])
    project.save(path)
    project.close()
    return path


@pytest.fixture(scope="session")
def big_project_template(tmp_path_factory) -> Path:
    path = make_big_project(tmp_path_factory.mktemp("big") / "template.h5")
    assert path.stat().st_size >= 50e6
    return path


def sensors(path: Path) -> dict:
    """The vessel sheet's sensors of project *path* (read-only open)."""
    from hydrosync_core.project import Project
    from hydrosync_core.project.vessel import vessel_config

    with Project.open(path, readonly=True) as project:
        return dict(vessel_config(project).get("sensors", {}))
