"""File → Run campaign…: the campaign runs off the GUI thread, shows progress and outcome."""

from __future__ import annotations

import logging

import pytest
from PySide6.QtCore import QTimer

from hydrosync_core.campaign.simulate import make_campaign


@pytest.fixture(scope="module")
def scheduler():
    """An existing one-worker Dask cluster (the dialog's 'Dask scheduler' field)."""
    from dask.distributed import LocalCluster

    cluster = LocalCluster(n_workers=1, threads_per_worker=1, processes=True,
                           dashboard_address=":0", silence_logs=logging.CRITICAL)
    yield cluster.scheduler_address
    cluster.close()


def wait_for(dialog, qtbot, timeout_s: float = 60.0) -> None:
    qtbot.waitUntil(lambda: not dialog.busy, timeout=int(timeout_s * 1000))


def test_menu_opens_the_dialog_and_a_bad_file_says_why(make_window, tmp_path):
    window = make_window()
    actions = [a.text() for a in window.menuBar().actions()[0].menu().actions()]
    assert "Run &campaign…" in actions
    dialog = window.open_campaign_dialog()
    bad = tmp_path / "bad.toml"
    bad.write_text("[analyses.nope]\n")
    assert not dialog.load(bad)
    assert "unknown analysis 'nope'" in dialog.plan.toPlainText()
    assert not dialog.run_button.isEnabled()
    dialog.close()


def test_campaign_runs_without_blocking_and_shows_the_summary(qtbot, tmp_path, scheduler,
                                                              make_window, ui):
    window = make_window()
    ui.open_path = str(make_campaign(tmp_path, days=2, analyses=("gnss_attitude",)))
    dialog = window.open_campaign_dialog()
    dialog.choose()
    assert "2 project(s) x 1 analysis(es)" in dialog.plan.toPlainText()
    dialog.scheduler_edit.setText(scheduler)
    dialog.run_button.click()
    assert dialog.busy and dialog.cancel_button.isEnabled() and not dialog.run_button.isEnabled()
    # The window stays responsive while the campaign runs: a GUI-thread timer keeps
    # ticking while the dialog is busy (a blocked event loop would deliver no tick until
    # the campaign had ended).
    seen_busy = []
    timer = QTimer()
    timer.timeout.connect(lambda: seen_busy.append(dialog.busy))
    timer.start(20)
    wait_for(dialog, qtbot)
    timer.stop()
    assert True in seen_busy
    assert dialog.result is not None and not dialog.result.failed
    assert dialog.table.rowCount() == 2 and dialog.table.columnCount() == 1
    assert dialog.table.item(0, 0).text().startswith("done")
    assert "Heading" in dialog.table.item(0, 0).toolTip()
    assert "2 done" in dialog.status.text()
    assert dialog.summary_button.isEnabled()
    assert dialog.bar.value() == 1000

    dialog.run_button.click()  # again: everything is up to date
    wait_for(dialog, qtbot)
    assert [o["status"] for o in dialog.result.outcomes] == ["up to date"] * 2
    dialog.close()


def test_cancel_stops_the_campaign(qtbot, tmp_path, scheduler, make_window):
    window = make_window()
    dialog = window.open_campaign_dialog()
    assert dialog.load(make_campaign(tmp_path, days=3, analyses=("gnss_attitude",)))
    dialog.scheduler_edit.setText(scheduler)
    dialog.run()
    dialog.cancel_button.click()
    wait_for(dialog, qtbot)
    assert dialog.result is None
    assert dialog.status.text().startswith("Cancelled")
    assert dialog.run_button.isEnabled()
    dialog.close()
