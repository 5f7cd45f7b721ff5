"""Regenerate the screenshots in ``docs/`` from the layout harness's artifact (#26).

``make screenshots`` (or ``.venv/bin/python scripts/docs_screenshots.py [--demo DIR]``):

1. runs the layout harness (``tests/gui/test_layout_harness.py``) and the Import dialog
   test with ``HYDROSYNC_SCREENSHOTS`` set to a scratch folder, offscreen: every panel
   and tab at 1366×768 and 1920×1080 on the demo project, checked as it is shot, so a
   picture in docs/ is one the checker passed;
2. when ``xvfb-run`` is installed, the Pool Calibration panel once more under Xvfb, where
   the OpenGL 3-D view replaces the 2-D projections;
3. copies the pictures the docs show (:data:`DOCS`) and renders the demo report's first
   page (``pdftoppm``) as ``docs/report-page.png``.

``--demo DIR`` reuses an earlier ``hydrosync demo --out DIR`` (with its ``stdout.txt`` and
``returncode.txt``, as the test fixture writes them); otherwise the demo runs once here.
``--keep DIR`` keeps the whole artifact folder (every panel, tab and size) there.
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DOCS_DIR = ROOT / "docs"
#: docs picture <- (artifact folder, harness file): "gl" is the Xvfb run.
DOCS = {
    "main-window-1366x768.png": ("plain", "gnss_attitude-1366x768.png"),
    "main-window.png": ("plain", "gnss_attitude-1920x1080.png"),
    "latency-panel.png": ("plain", "latency-1366x768.png"),
    "pool-panel.png": ("plain", "pool_calibration-1366x768-faces.png"),
    "pool-panel-3d-xvfb.png": ("gl", "pool_calibration-1366x768-faces.png"),
    "import-dialog.png": ("plain", "import-dialog-hourly.png"),
}
TESTS = ["tests/gui/test_layout_harness.py::test_panel_lays_out_on_the_screen",
         "tests/gui/test_import_logs.py::"
         "test_dialog_previews_and_imports_the_seapath_log_and_a_folder_of_hourly_logs"]


def run_demo(folder: Path) -> Path:
    """``hydrosync demo`` into *folder*, with the files the test fixture reads."""
    from hydrosync_gui.testing import run_demo_command

    proc = run_demo_command(folder)
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "stdout.txt").write_text(proc.stdout)
    (folder / "stderr.txt").write_text(proc.stderr)
    (folder / "returncode.txt").write_text(str(proc.returncode))
    if proc.returncode != 0:
        sys.exit(f"docs_screenshots: the demo failed:\n{proc.stderr[-2000:]}")
    return folder


def shoot(demo: Path, out: Path, tests: list[str], gl: bool = False) -> None:
    """Run *tests* with their screenshots written into *out*."""
    env = dict(os.environ, HYDROSYNC_DEMO_DIR=str(demo), HYDROSYNC_SCREENSHOTS=str(out),
               QT_QPA_PLATFORM="xcb" if gl else "offscreen")
    command = [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", *tests]
    if gl:
        command = ["xvfb-run", "-a", "-s", "-screen 0 1920x1080x24", *command]
    proc = subprocess.run(command, cwd=ROOT, env=env, capture_output=True, text=True)
    if proc.returncode != 0:
        sys.exit(f"docs_screenshots: the tests failed, no picture copied:\n"
                 f"{proc.stdout[-3000:]}")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--demo", type=Path, help="folder of an earlier `hydrosync demo`")
    parser.add_argument("--keep", type=Path, help="keep every screenshot in this folder")
    args = parser.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        scratch = Path(tmp)
        demo = args.demo if args.demo else run_demo(scratch / "demo")
        folders = {"plain": args.keep or scratch / "plain", "gl": scratch / "gl"}
        shoot(demo, folders["plain"], TESTS)
        has_xvfb = shutil.which("xvfb-run") is not None
        if has_xvfb:
            shoot(demo, folders["gl"], [f"{TESTS[0]}[pool_calibration-1366x768]"], gl=True)
        for name, (kind, pattern) in DOCS.items():
            found = sorted(folders[kind].glob(pattern)) if folders[kind].exists() else []
            if not found:
                print(f"  {name}: not made ({'no xvfb-run' if kind == 'gl' else pattern})")
                continue
            shutil.copyfile(found[0], DOCS_DIR / name)
            print(f"  docs/{name} <- {found[0].name}")
        report = demo / "demo-report.pdf"
        if report.exists() and shutil.which("pdftoppm"):
            subprocess.run(["pdftoppm", "-png", "-r", "90", "-f", "1", "-l", "1",
                            "-singlefile", str(report), str(DOCS_DIR / "report-page")],
                           check=True)
            print("  docs/report-page.png <- demo-report.pdf page 1")
    return 0


if __name__ == "__main__":
    sys.exit(main())
