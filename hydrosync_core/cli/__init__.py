"""The ``hydrosync`` command line.

Exit codes (``docs/formats.md``): 0 success; 2 bad input, with one line on stderr naming
the file and what is wrong; 3 finished with results the data do not determine; 130
interrupted (Ctrl-C), with one line saying what was and was not saved; 1 anything else.
Each sub-command lives in a module exposing ``register(subparsers)``: the project
commands here, each analysis's command in its core package, found through its plugin
spec (``PluginSpec.cli``).

Ctrl-C never prints a traceback: while the modules load, a handler installed before
any heavy import ends the process at once (exit 130, nothing can have been saved yet);
while a command runs, :mod:`hydrosync_core.interrupts` defers it around the renames that
publish files, so the message says truthfully what was saved. Library warnings and log
lines stay quiet unless ``-v``: the one-line error is the only line of a failure.
"""

from __future__ import annotations

import os
import signal
import sys
import threading


def _interrupted_while_loading(signum, frame) -> None:  # pragma: no cover - timing
    try:
        sys.stderr.write("hydrosync: interrupted (Ctrl-C) while starting: cancelled, "
                         "nothing was saved\n")
        sys.stderr.flush()
    finally:
        os._exit(130)


def _started_as_command() -> bool:
    name = os.path.basename(sys.argv[0]) if sys.argv and sys.argv[0] else ""
    return name == "-m" or (name.startswith("hydrosync") and "gui" not in name)


if _started_as_command() and threading.current_thread() is threading.main_thread():
    signal.signal(signal.SIGINT, _interrupted_while_loading)

import argparse  # noqa: E402 - after the Ctrl-C handler on purpose
import atexit  # noqa: E402
import contextlib  # noqa: E402
import gc  # noqa: E402
import importlib  # noqa: E402
import logging  # noqa: E402
import re  # noqa: E402

from hydrosync_core import __version__, atomic, interrupts  # noqa: E402
from hydrosync_core.errors import Cancelled, InputError  # noqa: E402

SUBCOMMAND_MODULES = {
    "hydrosync_core.cli.project_cmds": ("new", "import", "info", "vessel", "run"),
    "hydrosync_core.cli.report_cmd": ("report",),
    "hydrosync_core.cli.demo_cmd": ("demo",),
    "hydrosync_core.cli.batch_cmd": ("batch",),
}
"""Module of the project commands → the commands it registers (a hint for
:func:`build_parser`: a command missing here is still found, by the full parser)."""

EXIT_OK, EXIT_ERROR, EXIT_INPUT, EXIT_UNDETERMINED, EXIT_INTERRUPTED = 0, 1, 2, 3, 130


def _register_analyses(sub: argparse._SubParsersAction, command: str | None = None) -> None:
    """Add the command of every analysis that declares one (``PluginSpec.cli``); with
    *command*, only of the analyses whose id reads as that command (``heave-stats`` is
    ``heave_stats``)."""
    from hydrosync_core.plugins import discover
    from hydrosync_core.plugins.spec import load_object

    for found in discover():
        if found.spec is None or not found.spec.cli:
            continue
        if command is not None and _plain(found.spec.id) != _plain(command):
            continue
        try:
            load_object(found.spec.cli)(sub)
        except Exception as exc:  # a third-party command must not break the others
            if command is not None:
                return  # the full parser, built next, says so (once)
            logging.getLogger(__name__).error(
                "command of plugin %s could not be added: %s: %s", found.spec.id,
                type(exc).__name__, exc)


def _plain(name: str) -> str:
    return name.lower().replace("-", "_")


def _command_named(argv: list[str]) -> str | None:
    """The sub-command *argv* names, when that is plain without parsing (the global
    options take no value): None for help, the version, or anything unusual."""
    for token in argv:
        if token in ("-v", "--verbose"):
            continue
        return None if token.startswith("-") else token
    return None


class _Parser(argparse.ArgumentParser):
    """argparse with numbers in exponent form taken as values: ``--range -5e-1 5e-1``
    (argparse's own pattern knows ``-0.5`` but not ``-5e-1``, which it took for an option).
    Sub-command parsers are made of the same class."""

    def __init__(self, *args, **kwargs) -> None:
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = _NEGATIVE_NUMBER


_NEGATIVE_NUMBER = re.compile(r"^-(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?$")


def build_parser(command: str | None = None) -> argparse.ArgumentParser:
    """The ``hydrosync`` parser: every command, or, given *command*, that one alone.

    Registering a command imports its module (the project commands need h5py, an
    analysis its own modules): a command run in a new process registers only itself, so
    ``hydrosync latency`` starts without importing what the other commands need. A
    *command* not found among the modules that may define it (its analysis's id reads
    differently, or it is misspelt) gets the full parser, which then runs it or names
    the valid choices.
    """
    parser = _Parser(
        prog="hydrosync",
        description="HydroSync: sensor integration and calibration for hydrographic survey.",
    )
    parser.add_argument("--version", action="version", version=f"hydrosync {__version__}")
    parser.add_argument("-v", "--verbose", action="store_true", help="log progress details")
    parser.add_argument(
        "--break-lock", action="store_true",
        help="take over a project lock (and remove temporaries) left by HydroSync on another "
        "machine or container when older than 60 s; a lock held on this machine is never "
        "broken (may also follow the command)")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True
    for name, commands in SUBCOMMAND_MODULES.items():
        if command is not None and command not in commands:
            continue
        try:
            module = importlib.import_module(name)
        except ModuleNotFoundError as exc:
            if exc.name == name:  # the module is not written yet
                continue
            raise
        module.register(sub)
    if command is None or not sub.choices:
        _register_analyses(sub, command)
    if command is not None and command not in sub.choices:
        return build_parser()
    return parser


class _OwnRecords(logging.Filter):
    """Pass HydroSync's own log records; library records only with ``-v``."""

    def __init__(self) -> None:
        super().__init__()
        self.verbose = False

    def filter(self, record: logging.LogRecord) -> bool:
        if record.name == "hydrosync.notice":
            return False  # printed on stdout by _NoticeHandler
        return self.verbose or record.name.startswith("hydrosync")


class _NoticeHandler(logging.Handler):
    """``hydrosync.notice`` records (stale temporaries removed, …) as notes on stdout."""

    def emit(self, record: logging.LogRecord) -> None:
        # A closed stdout must not fail the command.
        with contextlib.suppress(Exception):
            print(f"note: {record.getMessage()}", file=sys.stdout, flush=True)


_FILTER = _OwnRecords()


def _configure_logging(verbose: bool) -> None:
    """Like ``logging.basicConfig`` (nothing changes if the root logger is set up by the
    host, e.g. pytest), with library records filtered and notices on stdout."""
    root = logging.getLogger()
    notice = logging.getLogger("hydrosync.notice")
    if not any(isinstance(h, _NoticeHandler) for h in notice.handlers):
        notice.addHandler(_NoticeHandler())
    _FILTER.verbose = verbose
    ours = getattr(root, "_hydrosync_cli", False)
    if root.handlers and not ours:
        return
    if not ours:
        handler = logging.StreamHandler()
        handler.setFormatter(logging.Formatter("%(levelname)s %(name)s: %(message)s"))
        handler.addFilter(_FILTER)
        root.addHandler(handler)
        root._hydrosync_cli = True
    root.setLevel(logging.INFO if verbose else logging.WARNING)


def _interrupt_message(command: str) -> str:
    saved = [os.path.basename(p) for p in interrupts.completed]
    if saved:
        return (f"{command}: interrupted (Ctrl-C); saved before the interrupt: "
                f"{', '.join(dict.fromkeys(saved))}")
    return f"{command}: interrupted (Ctrl-C): cancelled, nothing was saved"


FULL_COLLECTION_EVERY = 100
"""Collections of the middle generation between two full garbage collections while a
command runs (Python's default: 10). Loading numba, scipy and the analysis modules leaves
~10^5 objects that live until the process ends; every full collection walks all of them
(0.05-0.1 s), and a survey-day ``hydrosync latency`` made two of them for nothing."""

_freeze_at_exit = False


def _collect_less() -> tuple[int, int, int]:
    """Fewer full collections while the command runs (restored by the caller), none at
    exit: the interpreter's final collections walk every object (0.2-0.4 s after a
    latency run) to free memory the system takes back anyway, so everything alive then
    is frozen first (:func:`gc.freeze`, registered once, and only in a ``hydrosync``
    process: an in-process caller such as the GUI or a test keeps its own collector).
    ``benchmarks/bench_cli_gc.py`` measures what this saves (1.4 s of a 500-line
    ``hydrosync latency`` on a loaded two-core machine)."""
    global _freeze_at_exit
    if not _freeze_at_exit and _started_as_command():
        atexit.register(gc.freeze)
        _freeze_at_exit = True
    thresholds = gc.get_threshold()
    gc.set_threshold(thresholds[0], thresholds[1], max(thresholds[2], FULL_COLLECTION_EVERY))
    return thresholds


def main(argv: list[str] | None = None) -> int:
    in_main_thread = threading.current_thread() is threading.main_thread()
    interrupts.reset()
    undo_interrupts = interrupts.install()
    logging.captureWarnings(True)
    thresholds = _collect_less()
    command = "hydrosync"
    try:
        try:
            if argv is None:
                argv = sys.argv[1:]
            argv = [str(a) for a in argv]
            atomic.BREAK_LOCK, argv = _break_lock_option(argv)
            parser = build_parser(_command_named(argv))
            args = parser.parse_args(argv)
            command = f"hydrosync {args.command}"
            _configure_logging(args.verbose)
            code = int(args.func(args) or 0)
            if interrupts.interrupted():  # held back during clean-up, never raised
                raise KeyboardInterrupt
            return code
        except InputError as exc:
            if interrupts.interrupted():  # e.g. h5py's lock turned a Ctrl-C into a "corrupted
                _ignore_further_interrupts(in_main_thread)  # project": the file is intact
                print(_interrupt_message(command), file=sys.stderr)
                return _end_interrupted(in_main_thread, loading=command == "hydrosync")
            print(f"{command}: {exc.one_line()}", file=sys.stderr)
            return EXIT_INPUT
        except BrokenPipeError:  # ``hydrosync info P.h5 | head``: the reader left, as
            _silence_stdout()      # it may; what it read is all it wanted (as ``cat``)
            return EXIT_OK
        except (Cancelled, KeyboardInterrupt):
            _ignore_further_interrupts(in_main_thread)
            print(_interrupt_message(command), file=sys.stderr)
            return _end_interrupted(in_main_thread, loading=command == "hydrosync")
        except Exception as exc:
            if interrupts.interrupted():  # a Ctrl-C a library turned into another error
                _ignore_further_interrupts(in_main_thread)
                print(_interrupt_message(command), file=sys.stderr)
                return _end_interrupted(in_main_thread, loading=command == "hydrosync")
            if atomic.is_disk_full(exc):  # a write outside the atomic helpers
                target = getattr(exc, "filename", None) or "an output file"
                print(f"{command}: {atomic.disk_full(target).one_line()}", file=sys.stderr)
                return EXIT_INPUT
            if os.environ.get("HYDROSYNC_DEBUG"):
                raise
            text = " ".join(f"{type(exc).__name__}: {exc}".split())[:300]
            print(f"{command}: internal error: {text} (set HYDROSYNC_DEBUG=1 for the "
                  "traceback)", file=sys.stderr)
            return EXIT_ERROR
    except KeyboardInterrupt:  # a second Ctrl-C while reporting the first
        return EXIT_INTERRUPTED
    finally:
        gc.set_threshold(*thresholds)
        logging.captureWarnings(False)
        undo_interrupts()
        if in_main_thread and _started_as_command():
            # The command is over: a Ctrl-C while the interpreter shuts down must neither
            # kill it silently nor print anything (Python keeps SIG_IGN through shutdown).
            signal.signal(signal.SIGINT, signal.SIG_IGN)


def _end_interrupted(in_main_thread: bool, loading: bool) -> int:
    """Exit code of an interrupted command; a ``hydrosync`` process interrupted while its
    modules load (*loading*: before the command started) ends here, at once.

    A Ctrl-C that lands inside an import (the parser loads the command modules) can leave a
    compiled extension half initialised, and the interpreter's shutdown may then crash in
    it: exit -11 after the right message (``tests/reliability/test_signals.py``). Before
    the command starts nothing is open and nothing can have been saved, so, as the handler
    installed while the first modules load does, the process skips the shutdown. Later the
    shutdown runs as usual (it closes projects and releases their locks); an in-process
    caller (the GUI, a test) always gets the code back.
    """
    if loading and in_main_thread and _started_as_command():
        for stream in (sys.stdout, sys.stderr):
            with contextlib.suppress(Exception):
                stream.flush()
        os._exit(EXIT_INTERRUPTED)
    return EXIT_INTERRUPTED


def _break_lock_option(argv: list[str]) -> tuple[bool, list[str]]:
    """``--break-lock`` anywhere before ``--`` (it reads naturally after the command)."""
    end = argv.index("--") if "--" in argv else len(argv)
    given = "--break-lock" in argv[:end]
    if given:
        argv = [a for a in argv[:end] if a != "--break-lock"] + argv[end:]
    return given, argv


def _silence_stdout() -> None:
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError, AttributeError):  # not a real file (tests)
        pass


def _ignore_further_interrupts(in_main_thread: bool) -> None:
    if in_main_thread:
        signal.signal(signal.SIGINT, signal.SIG_IGN)


if __name__ == "__main__":
    sys.exit(main())
