"""The ``hydrosync`` command line.

Exit codes (``formats.md``): 0 success; 2 bad input, with one line on stderr naming the
file and what is wrong; 1 anything else. Each sub-command lives in its own module
exposing ``register(subparsers)``.
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
    "hydrosync_core.methods.latency.cli",
    "hydrosync_core.methods.pool_calibration.cli",
    "hydrosync_core.cli.report_cmd",
    "hydrosync_core.cli.demo_cmd",
)


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
