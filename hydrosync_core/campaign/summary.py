"""The campaign summary: ``summary.csv`` and ``summary.html`` (with the trend plots).

``summary.csv`` has one row per project × step (import, each analysis, report): campaign,
project, date, path, step, status, seconds, run_utc, worker, warnings (`` | ``-joined),
message, key_figures (the analysis's own summary rows, ``quantity: value; …``), then one
column per numeric result attribute met in the campaign (``latency_s``, ``ci95_low``,
``roll_deg``, …; empty where a step has none).

``summary.html`` is one self-contained page: where and how long the campaign ran, the
trend plots (latency per day with its 95 % interval; the boresight angles per day with
±1.96 σ when the campaign holds pool calibrations), and a table project × analysis with
status, key figures, warnings and duration. Matplotlib draws the plots (Agg backend, PNG
embedded as base64). Both files are written atomically.
"""

from __future__ import annotations

import base64
import csv
import html
import io
import math
from pathlib import Path

from hydrosync_core.atomic import write_text_atomic
from hydrosync_core.campaign.steps import DONE, FAILED, NOT_APPLICABLE, UP_TO_DATE

FIXED = ["campaign", "project", "date", "path", "step", "status", "seconds", "run_utc",
         "worker", "warnings", "message", "key_figures"]

COLOURS = {DONE: "#d9f2d9", UP_TO_DATE: "#e6f0fa", NOT_APPLICABLE: "#f0f0f0",
           "skipped": "#fde9c8", FAILED: "#f8d0d0"}


def _day(outcome: dict) -> str | None:
    return outcome.get("date") or outcome.get("data_date")


def csv_rows(result) -> tuple[list[str], list[list]]:
    numeric = sorted({k for o in result.outcomes for k in (o.get("numbers") or {})})
    rows = []
    for o in result.outcomes:
        numbers = o.get("numbers") or {}
        rows.append([result.campaign.name, o["project"], _day(o) or "", o["path"], o["step"],
                     o["status"], f"{o.get('seconds', 0.0):.3f}", o.get("run_utc") or "",
                     o.get("worker", ""), " | ".join(o.get("warnings") or []),
                     o.get("message", ""),
                     "; ".join(f"{q}: {v}" for q, v in o.get("rows") or [])]
                    + [_num(numbers.get(k)) for k in numeric])
    return FIXED + numeric, rows


def _num(value) -> str:
    if value is None or not math.isfinite(value):
        return ""
    return f"{value:.9g}"


def trend_series(result) -> list[tuple[str, str, list]]:
    """``(title, unit, [(label, [(x label, value, low, high)])])`` of the trends with data."""
    from hydrosync_core.plugins import plugin_specs

    out = []
    for analysis, trend in ((s.id, t) for s in plugin_specs() for t in s.trends):
        steps = [o for o in result.outcomes if o["step"] == analysis and o.get("numbers")]
        if not steps:
            continue
        steps.sort(key=lambda o: (_day(o) or "9999", o["project"]))
        lines = []
        for item in trend.series:
            points = []
            for o in steps:
                n = o["numbers"]
                value = n.get(item.value)
                if value is None or not math.isfinite(value):
                    continue
                if item.sigma and n.get(item.sigma) is not None:
                    lo, hi = value - 1.96 * n[item.sigma], value + 1.96 * n[item.sigma]
                else:
                    lo, hi = n.get(item.low, math.nan), n.get(item.high, math.nan)
                points.append((_day(o) or o["project"], value, lo, hi, o["project"]))
            if points:
                lines.append((item.label, points))
        if lines:
            out.append((trend.title, trend.unit, lines))
    return out


def trend_png(title: str, unit: str, lines: list) -> bytes:
    """One trend plot as PNG bytes (matplotlib, Agg)."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    from matplotlib.figure import Figure

    fig = Figure(figsize=(8.0, 3.2), dpi=100)
    ax = fig.add_subplot(1, 1, 1)
    labels: list[str] = []
    for _label, points in lines:
        for x, *_ in points:
            if x not in labels:
                labels.append(x)
    labels.sort()
    index = {x: i for i, x in enumerate(labels)}
    for k, (label, points) in enumerate(lines):
        shift = (k - (len(lines) - 1) / 2) * 0.08
        xs = [index[p[0]] + shift for p in points]
        ys = [p[1] for p in points]
        lo = [p[1] - p[2] if math.isfinite(p[2]) else 0.0 for p in points]
        hi = [p[3] - p[1] if math.isfinite(p[3]) else 0.0 for p in points]
        ax.errorbar(xs, ys, yerr=[lo, hi], fmt="o-", capsize=3, label=label, lw=1)
    ax.set_xticks(range(len(labels)))
    ax.set_xticklabels(labels, rotation=45 if len(labels) > 6 else 0, ha="right"
                       if len(labels) > 6 else "center", fontsize=8)
    ax.set_ylabel(unit)
    ax.set_title(title, fontsize=10)
    ax.grid(alpha=0.3)
    if len(lines) > 1:
        ax.legend(fontsize=8)
    fig.tight_layout()
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png")
    return buffer.getvalue()


def _cell(outcome: dict | None) -> str:
    if outcome is None:
        return "<td></td>"
    status = outcome["status"]
    parts = [f"<b>{html.escape(status)}</b> ({outcome.get('seconds', 0.0):.1f} s)"]
    rows = outcome.get("rows") or []
    if rows:
        parts.append("<br>".join(f"{html.escape(q)}: {html.escape(v)}" for q, v in rows))
    if outcome.get("message") and status not in (DONE, UP_TO_DATE):
        parts.append(f"<i>{html.escape(outcome['message'])}</i>")
    for w in outcome.get("warnings") or []:
        parts.append(f"<span class='warn'>⚠ {html.escape(w)}</span>")
    colour = COLOURS.get(status, "#ffffff")
    return f"<td style='background:{colour}'>" + "<br>".join(parts) + "</td>"


def html_page(result) -> str:
    from hydrosync_core.campaign.engine import status_counts

    c = result.campaign
    steps = list(dict.fromkeys(o["step"] for o in result.outcomes))
    by = {(o["project"], o["step"]): o for o in result.outcomes}
    projects = list(dict.fromkeys(o["project"] for o in result.outcomes))
    day = {o["project"]: _day(o) for o in result.outcomes if _day(o)}
    out = ["<!DOCTYPE html><html><head><meta charset='utf-8'>",
           f"<title>{html.escape(c.name)}: campaign summary</title>",
           "<style>body{font-family:sans-serif;margin:1.5em} table{border-collapse:collapse}"
           " td,th{border:1px solid #bbb;padding:4px 6px;vertical-align:top;font-size:0.85em}"
           " .warn{color:#8a5a00}</style></head><body>",
           f"<h1>{html.escape(c.name)}</h1>",
           f"<p>Campaign file {html.escape(c.path)}; {len(projects)} project(s); ran on "
           f"{html.escape(result.where)} ({result.workers} worker(s)) in "
           f"{result.wall_s:.1f} s. Steps: {html.escape(status_counts(result))}.</p>"]
    trends = trend_series(result)
    if trends:
        out.append("<h2>Trends</h2>")
    for title, unit, lines in trends:
        data = base64.b64encode(trend_png(title, unit, lines)).decode("ascii")
        out.append(f"<p><img alt='{html.escape(title)}' src='data:image/png;base64,{data}'>"
                   "</p>")
    out.append("<h2>Projects × analyses</h2><table><tr><th>project</th><th>date</th>"
               + "".join(f"<th>{html.escape(s)}</th>" for s in steps) + "</tr>")
    for p in projects:
        out.append(f"<tr><td>{html.escape(p)}</td><td>{html.escape(day.get(p, ''))}</td>"
                   + "".join(_cell(by.get((p, s))) for s in steps) + "</tr>")
    out.append("</table>")
    failed = result.failed
    if failed:
        out.append("<h2>Failures</h2><ul>")
        out += [f"<li>{html.escape(o['project'])} / {html.escape(o['step'])}: "
                f"{html.escape(o.get('message', ''))}</li>" for o in failed]
        out.append("</ul>")
    out.append("</body></html>")
    return "\n".join(out)


def write_summary(result) -> list[Path]:
    """Write ``summary.csv`` and ``summary.html`` into the campaign's output folder."""
    folder = Path(result.campaign.outputs.dir)
    folder.mkdir(parents=True, exist_ok=True)
    header, rows = csv_rows(result)
    csv_path, html_path = folder / "summary.csv", folder / "summary.html"
    text = io.StringIO()
    writer = csv.writer(text, lineterminator="\n")
    writer.writerow(header)
    writer.writerows(rows)
    write_text_atomic(csv_path, lambda fh: fh.write(text.getvalue()))
    page = html_page(result)
    write_text_atomic(html_path, lambda fh: fh.write(page))
    return [csv_path, html_path]
