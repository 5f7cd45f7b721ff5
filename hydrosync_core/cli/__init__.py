"""The ``hydrosync`` command line.

Exit codes (``docs/formats.md``): 0 success; 2 bad input, with one line on stderr naming
the file and what is wrong; 1 anything else. Each sub-command lives in a module exposing
``register(subparsers)``: the project commands here, each analysis's command in its core
package, found through its plugin spec (``PluginSpec.cli``).
"""

from __future__ import annotations

import argparse
import importlib
import logging
import os
import sys

from hydrosync_core import __version__
from hydrosync_core.errors import Cancelled, InputError

SUBCOMMAND_MODULES = (
    "hydrosync_core.cli.project_cmds",
    "hydrosync_core.cli.report_cmd",
    "hydrosync_core.cli.demo_cmd",
)


def _register_analyses(sub: argparse._SubParsersAction) -> None:
    """Add the command of every analysis that declares one (``PluginSpec.cli``)."""
    from hydrosync_core.plugins import discover
    from hydrosync_core.plugins.spec import load_object

    for found in discover():
        if found.spec is None or not found.spec.cli:
            continue
        try:
            load_object(found.spec.cli)(sub)
        except Exception as exc:  # a third-party command must not break the others
            logging.getLogger(__name__).error(
                "command of plugin %s could not be added: %s: %s", found.spec.id,
                type(exc).__name__, exc)


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="hydrosync",
        description="HydroSync: sensor integration and calibration for hydrographic survey.",
    )
    parser.add_argument("--version", action="version", version=f"hydrosync {__version__}")
    parser.add_argument("-v", "--verbose", action="store_true", help="log progress details")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True
    for name in SUBCOMMAND_MODULES:
        try:
            module = importlib.import_module(name)
        except ModuleNotFoundError as exc:
            if exc.name == name:  # the module is not written yet
                continue
            raise
        module.register(sub)
    _register_analyses(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    logging.basicConfig(
        level=logging.INFO if args.verbose else logging.WARNING,
        format="%(levelname)s %(name)s: %(message)s",
    )
    try:
        return int(args.func(args) or 0)
    except InputError as exc:
        print(f"hydrosync {args.command}: {exc.one_line()}", file=sys.stderr)
        return 2
    except (Cancelled, KeyboardInterrupt):
        print(f"hydrosync {args.command}: cancelled", file=sys.stderr)
        return 1
    except Exception as exc:
        if os.environ.get("HYDROSYNC_DEBUG"):
            raise
        print(
            f"hydrosync {args.command}: internal error: {type(exc).__name__}: {exc} "
            "(set HYDROSYNC_DEBUG=1 for the traceback)",
            file=sys.stderr,
        )
        return 1


if __name__ == "__main__":
    sys.exit(main())
