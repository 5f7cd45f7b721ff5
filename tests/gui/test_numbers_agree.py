"""The numbers a surveyor signs read the same in the panel, the CLI and the PDF (#26).

For each analysis, the key results are its ``summary(project)`` rows — what the PDF's
summary table and ``hydrosync demo`` print. Every number in them (with its digits: "0.296"
is not "0.2960" nor "0.30") must also be printed, digit for digit, by

* the CLI: the ``hydrosync demo`` output,
* the PDF: the text of ``demo-report.pdf``,
* the panel: the text of its labels and the cells of its tables, on the demo project.

A panel that prints a number with other digits (the pool iteration table's "+8.15e-01°"
where the PDF shows 0.8148) fails here. Panels that other helpers own and that fail are
marked xfail with the reason, and pass again by themselves once fixed.
"""

from __future__ import annotations

import re
import subprocess

import pytest
from PySide6.QtCore import QEvent, Qt
from PySide6.QtWidgets import QAbstractItemView, QApplication, QLabel

PLUGINS = ["latency", "pool_calibration", "gnss_attitude", "gins_smoother", "tilt_alignment"]
NUMBER = re.compile(r"(?<![\w.])[-+\u2212]?\d+(?:\.\d+)?(?:e[-+]?\d+)?(?![\w.])")
#: Panels known to print a summary number with other digits, with the reason: none now.
KNOWN: dict[str, str] = {}


def numbers(text: str) -> set[str]:
    """The numbers written in *text*, as written (the minus sign made ASCII)."""
    text = text.replace("\u2212", "-").replace("\u00a0", " ")
    return {m.lstrip("+") for m in NUMBER.findall(text)}


def _plain(html: str) -> str:
    from PySide6.QtGui import QTextDocument

    doc = QTextDocument()
    doc.setHtml(html)
    return doc.toPlainText()


def panel_text(panel) -> str:
    """Everything the panel prints: its labels and every cell and header of its tables."""
    parts = [_plain(label.text()) for label in panel.findChildren(QLabel) if label.text()]
    for view in panel.findChildren(QAbstractItemView):
        model = view.model()
        if model is None:
            continue
        for column in range(model.columnCount()):
            parts.append(str(model.headerData(column, Qt.Orientation.Horizontal) or ""))
            for row in range(model.rowCount()):
                parts.append(str(model.index(row, column).data() or ""))
    return "\n".join(parts)


@pytest.fixture(scope="module")
def demo_texts(hydrosync_demo):
    """(CLI output, PDF text) of the session's demo run."""
    from hydrosync_core.demo import DEMO_REPORT

    pdf = hydrosync_demo / DEMO_REPORT
    if not pdf.exists():
        pytest.skip("the demo wrote no report: "
                    + (hydrosync_demo / "stderr.txt").read_text()[-300:])
    text = subprocess.run(["pdftotext", "-layout", str(pdf), "-"], capture_output=True,
                          text=True, check=True).stdout
    return (hydrosync_demo / "stdout.txt").read_text(), text


@pytest.mark.parametrize("plugin", PLUGINS)
def test_panel_cli_and_pdf_print_the_same_numbers(qtbot, make_window, hydrosync_demo,
                                                 demo_texts, plugin):
    from hydrosync_core.demo import DEMO_PROJECT
    from hydrosync_core.plugins import discover, load_object
    from hydrosync_core.project import Project

    project = Project.open(hydrosync_demo / DEMO_PROJECT, readonly=True)
    window = make_window(project, discover=discover)
    ids = [e.spec.id for e in window.host.entries]
    spec = window.host.entries[ids.index(plugin)].spec
    summary = load_object(f"{spec.report_section.partition(':')[0]}:summary")
    rows = summary(project)
    wanted = {(quantity, n) for quantity, value in rows for n in numbers(value)}
    assert wanted, f"{plugin}: its summary prints no number"
    window.tabs.setCurrentIndex(ids.index(plugin))
    qtbot.wait(30)
    assert window.wait_idle(60.0)
    QApplication.sendPostedEvents(None, QEvent.Type.DeferredDelete)
    panel = window.current_panel()
    # The Latency panel reads the raw series on a thread of its own (not a task): let it
    # end before the window closes.
    qtbot.waitUntil(lambda: not getattr(panel, "_loading", False), timeout=60_000)
    shown = numbers(panel_text(panel))
    cli, pdf = (numbers(t) for t in demo_texts)
    missing = {where: sorted(f"{q}: {n}" for q, n in wanted if n not in found)
               for where, found in (("CLI", cli), ("PDF", pdf), ("panel", shown))}
    missing = {k: v for k, v in missing.items() if v}
    if missing and plugin in KNOWN:
        pytest.xfail(KNOWN[plugin])
    assert not missing, missing


def test_number_tokens_keep_their_digits():
    assert numbers("-44.193 ± 0.004°") == {"-44.193", "0.004"}
    assert numbers("Δt 0.2960 s, 13 of 13 lines, σ 6.80 ms") == {"0.2960", "13", "6.80"}
    assert numbers("\u22120.605 m; 1.7/1.4/2.7 mm") == {"-0.605", "1.7", "1.4", "2.7"}
    assert numbers("+8.15e-01°") == {"8.15e-01"}
    assert "0.30" not in numbers("0.296")


def test_demo_truth_has_the_digits_of_the_results_beside_it():
    """The simulated truth is printed exactly (up to 8 significant digits, trailing
    zeros dropped), not to 4 beside results printed to 6 or 8: a truth
    512.34 once read "512.3" beside the estimate 512.3404."""
    from hydrosync_core.demo import truth_text

    truth = {"tip_enu": [512.34041, 1023.872, 3.2166], "roll": -44.2, "n": 4,
             "latency_s": 0.29}
    assert truth_text(truth) == ("tip_enu [512.34041, 1023.872, 3.2166], roll -44.2, n 4, "
                                 "latency_s 0.29")
