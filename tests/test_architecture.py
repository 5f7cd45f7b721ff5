"""The core stays Qt-free: importing it, the CLI and every plugin spec loads no Qt.

Runs in a fresh interpreter (this test process may already have Qt loaded). Every
``hydrosync_core`` module but ``__main__`` is imported (``pkgutil.walk_packages``), the
CLI's parser is built (importing its sub-command modules), and the module of each
``hydrosync.plugins`` entry point (the plugin's Qt-free ``__init__``) is imported;
afterwards no PySide6, shiboken6 or pyqtgraph module may be in ``sys.modules``. A module
that fails to import fails the test too.
"""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap

import pytest

FORBIDDEN = ("PySide6", "shiboken6", "pyqtgraph", "PyQt5", "PyQt6")

SCRIPT = textwrap.dedent(
    """
    import importlib, json, pkgutil, sys, traceback
    from importlib.metadata import entry_points

    import hydrosync_core

    imported, failed = [], {}

    def load(name):
        try:
            importlib.import_module(name)
            imported.append(name)
        except Exception as exc:
            failed[name] = f"{type(exc).__name__}: {exc}"

    for info in pkgutil.walk_packages(hydrosync_core.__path__, "hydrosync_core."):
        if not info.name.endswith(".__main__"):  # runs the program when imported
            load(info.name)
    try:
        from hydrosync_core.cli import build_parser
        build_parser()
        imported.append("hydrosync_core.cli:build_parser()")
    except Exception as exc:
        failed["hydrosync_core.cli"] = f"{type(exc).__name__}: {exc}"
    for ep in entry_points(group="hydrosync.plugins"):
        load(ep.value.partition(":")[0])
    forbidden = sorted(m for m in sys.modules if m.split(".")[0] in FORBIDDEN)
    print(json.dumps({"imported": imported, "failed": failed, "forbidden": forbidden}))
    """
)


def run_probe() -> dict:
    code = f"FORBIDDEN = {FORBIDDEN!r}\n" + SCRIPT
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=240, env={"QT_QPA_PLATFORM": "offscreen",
                                            "PATH": "/usr/bin:/bin", "HOME": "/tmp"})
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout.strip().splitlines()[-1])


@pytest.fixture(scope="module")
def probe() -> dict:
    return run_probe()


def test_core_cli_and_plugin_specs_import(probe):
    assert "hydrosync_core.project.model" in probe["imported"]
    assert "hydrosync_core.cli:build_parser()" in probe["imported"]
    assert probe["failed"] == {}, "modules failed to import: " + json.dumps(probe["failed"])


def test_no_qt_is_loaded_by_the_core(probe):
    assert probe["forbidden"] == [], f"Qt loaded by the core: {probe['forbidden']}"


SPEC_PROBE = textwrap.dedent(
    """
    import json, sys
    sys.path.insert(0, {example!r})
    import importlib
    importlib.import_module({module!r})
    heavy = sorted(m for m in sys.modules
                   if m.split(".")[0] in ("scipy", "open3d", "PySide6", "shiboken6",
                                          "pyqtgraph", "reportlab", "laspy", "h5py", "numba")
                   or (m.startswith("hydrosync_core.methods.") and m.count(".") >= 3))
    print(json.dumps(heavy))
    """
)


def _spec_modules() -> list[str]:
    from importlib.metadata import entry_points

    found = sorted({ep.value.partition(":")[0] for ep in entry_points(group="hydrosync.plugins")})
    return found + ["hydrosync_heave_stats"]


@pytest.mark.parametrize("module", _spec_modules())
def test_importing_a_spec_is_cheap(module):
    """A spec is declared, then loaded lazily: no scipy, open3d, Qt, nor method modules."""
    from pathlib import Path

    example = str(Path(__file__).resolve().parents[1] / "examples" / "heave_stats")
    done = subprocess.run([sys.executable, "-c", SPEC_PROBE.format(example=example,
                                                                   module=module)],
                          capture_output=True, text=True, timeout=120,
                          env={"PATH": "/usr/bin:/bin", "HOME": "/tmp"})
    assert done.returncode == 0, done.stderr
    assert json.loads(done.stdout.strip().splitlines()[-1]) == []
