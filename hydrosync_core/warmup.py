"""Compile and cache every analysis's numba kernels once, when HydroSync is installed.

numba compiles a kernel on its first use and keeps the machine code in ``__pycache__``.
The latency estimate's line scan alone takes ~15 s to compile and the GNSS/INS
smoother's filter ~35 s, which a user's first run (a panel's progress bar standing
still, or the first ``hydrosync latency``) would otherwise wait for. ``make install``
runs this module after installing the package. Each analysis declares its own warm-up
(``PluginSpec.warmup``): this module knows none of them by name.

Run: ``python -m hydrosync_core.warmup``.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable


def steps() -> list[tuple[str, Callable[[], None]]]:
    """(analysis name, warm-up function) of every plugin that declares one, each on its
    own (one failing leaves the others compiled)."""
    from hydrosync_core.plugins import load_object, plugin_specs

    out = []
    for spec in plugin_specs():
        if spec.warmup:
            def step(dotted=spec.warmup):
                load_object(dotted)()
            out.append((spec.name, step))
    return out


def main() -> int:
    start = time.perf_counter()
    done = []
    for name, step in steps():
        try:
            step()
        except Exception as exc:  # noqa: BLE001 - a warm-up must never fail an install
            print(f"hydrosync warm-up: {name} kernels not compiled ahead ({exc}); they will "
                  "be on first use", file=sys.stderr)
        else:
            done.append(name)
    if done:
        print(f"hydrosync warm-up: compiled kernels cached in "
              f"{time.perf_counter() - start:.0f} s ({', '.join(done)})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
