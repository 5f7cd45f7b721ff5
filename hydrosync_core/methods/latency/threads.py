"""Per-line work on a small thread pool (the compiled kernels and the FFTs release the GIL)."""

from __future__ import annotations

from concurrent.futures import ThreadPoolExecutor

from hydrosync_core.progress import check_cancel, report

SCAN_THREADS = 2
"""Lines processed concurrently (the compiled kernels and the FFTs release the GIL)."""


LINES_PER_TASK = 4
"""Lines one thread-pool task takes in turn: a future per line cost ~25 µs of the main
thread's interpreter time (1500 per survey day), which the scan threads wait on."""


def per_line(task, count: int, names: list, progress, cancel) -> list:
    """``task(i)`` for every line index, in order, on up to SCAN_THREADS threads."""
    def run(lo: int) -> list:
        return [task(i) for i in range(lo, min(lo + LINES_PER_TASK, count))]

    out: list = []
    with ThreadPoolExecutor(SCAN_THREADS) as pool:
        futures = [pool.submit(run, lo) for lo in range(0, count, LINES_PER_TASK)]
        try:
            for future in futures:
                check_cancel(cancel)
                report(progress, len(out) / max(count, 1), f"line {names[len(out)]}")
                out += future.result()
        except BaseException:
            for future in futures:
                future.cancel()
            raise
    return out
