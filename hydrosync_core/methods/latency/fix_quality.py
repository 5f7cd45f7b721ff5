"""Which GNSS heights enter the latency, by fix quality (GGA quality indicator).

Heights of mixed quality are never mixed silently: with RTK-fixed epochs (quality 4) in the
record only those are used by default and the others are counted in a warning; without any,
every epoch is used with a warning that names the qualities (the Seapath logs'
INS-blended GGA report quality 1). ``fix_qualities`` chooses the qualities explicitly.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from hydrosync_core.errors import InputError
from hydrosync_core.methods.latency.params import parse_qualities

NAMES = {0: "invalid", 1: "autonomous", 2: "DGPS", 3: "PPS", 4: "RTK fixed", 5: "RTK float",
         6: "dead reckoning/INS", 7: "manual", 8: "simulated"}
RTK_FIXED = 4


def _counts(quality: np.ndarray) -> str:
    values, counts = np.unique(quality[np.isfinite(quality)].astype(int), return_counts=True)
    parts = [f"{n} {NAMES.get(int(v), f'quality {v}')} (q {v})"
             for v, n in zip(values, counts, strict=True)]
    missing = int(np.sum(~np.isfinite(quality)))
    if missing:
        parts.append(f"{missing} without quality")
    return ", ".join(parts)


def screen_fixes(gnss: Mapping, choice: str = "auto") -> tuple[dict, list[str]]:
    """(gnss restricted to the chosen fix qualities, warnings). A table without a
    ``quality`` column is returned as it is."""
    if "quality" not in gnss:
        return dict(gnss), []
    quality = np.asarray(gnss["quality"], dtype=float)
    wanted = parse_qualities(choice)
    if wanted is None:
        if np.any(quality == RTK_FIXED):
            wanted = (RTK_FIXED,)
        else:
            return dict(gnss), [f"GNSS heights of quality {_counts(quality)}: no RTK-fixed "
                                "epoch, all used (INS-blended or code heights carry their "
                                "own filtering and noise)"]
    keep = np.isin(quality, wanted)
    if not keep.any():
        raise InputError("gnss", f"no epoch of fix quality {','.join(map(str, wanted))} "
                         f"(the log holds {_counts(quality)})", field="quality")
    warnings = []
    if not keep.all():
        warnings.append(f"{int((~keep).sum())} GNSS epochs not of fix quality "
                        f"{','.join(map(str, wanted))} excluded ({_counts(quality[~keep])})")
    n = quality.size
    return {k: (np.asarray(v)[keep] if np.ndim(v) == 1 and len(v) == n else v)
            for k, v in gnss.items()}, warnings
