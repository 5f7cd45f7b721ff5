"""GNSS-array attitude on a real array: the UPV four-antenna car roof against a MEMS INS.

Four network-RTK receivers on a 0.8 m x 0.8 m square on a car roof, 1 Hz, 2022-10-20 (UPV
MUIGG course data, ``shared/data/upv-gnss4ant``, see its SOURCE.md), solved with every
method (LSQ, Wahba, direct) and compared with

- the recording's own array attitude (the course software),
- the SBG Ellipse2-N MEMS INS at 1 Hz (whole run) and 50 Hz (session 4, driving),

after the clock offset (INS tags 18.0 s behind GNSS; re-estimated from the heading here)
with heading and roll wrapped. Each difference is split into a constant offset (mounting
misalignment, layout and INS heading bias: the inlier mean) and the scatter (inlier std);
gross outliers (> max(5 robust sigma, 2 deg)) are counted apart. Then the static scatter
(session 2, car standing 60 s) next to the predicted precision.
"""

from __future__ import annotations

import sys
import time

from hydrosync_core.datasets import shared_data_dir
from hydrosync_core.methods.gnss_attitude import upv_array


def main() -> int:
    folder = shared_data_dir() / "upv-gnss4ant"
    if not (folder / "SOURCE.md").exists():
        print(f"skipped: real array data set {folder} not present")
        return 0
    t0 = time.perf_counter()
    res = upv_array.compare_all(folder)
    print("UPV four-antenna array (0.8 m square, network RTK, 1 Hz) vs INS and the "
          "recording's attitude")
    print(upv_array.format_report(res))
    print(f"\n(read, solved and compared in {time.perf_counter() - t0:.1f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
