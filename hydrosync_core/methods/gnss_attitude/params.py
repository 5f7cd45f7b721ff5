"""Parameters of the GNSS-array attitude: the one place they are declared.

The panel form, the ``hydrosync attitude`` flags, ``hydrosync run gnss_attitude --param``,
the stored parameters and the report's parameter table all derive from
:class:`GnssAttitudeParams`. Imports only the standard library.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from hydrosync_core.errors import InputError
from hydrosync_core.params import Params, param

#: Estimators: iterative weighted least squares (Liu et al. eqs. 17-24), the three-antenna
#: direct method (Liu et al. eqs. 1-16) and the closed-form weighted Wahba solution.
METHODS = ("lsq", "direct", "wahba")
#: Which RTKLIB quality flags are accepted: fixed (Q=1), fixed or float (Q<=2), any (Q>=1).
QUALITIES = ("fixed", "float", "any")
#: Position weights: the std/covariance columns of the files, or the a-priori σ below.
WEIGHTS = ("file", "apriori")


@dataclass(frozen=True)
class GnssAttitudeParams(Params):
    """Parameters of the attitude from a GNSS antenna array.

    Lengths in metres, times in seconds (the files' GPS time of week), angles in degrees.
    """

    SCHEMA_VERSION: ClassVar[int] = 1

    method: str = param(
        "lsq", label="Reported method", choices=METHODS,
        help="solution written to attitude.csv and summarised: lsq = iterative weighted "
             "least squares (Liu et al.), direct = three-antenna direct method (Liu et al.), "
             "wahba = closed-form optimal rotation; all three are always computed")
    min_quality: str = param(
        "fixed", label="Accepted solutions", choices=QUALITIES,
        help="antenna positions used: fixed = RTK fixed only (Q=1), float = fixed or float "
             "(Q<=2), any = every solution")
    length_tolerance_m: float = param(
        0.05, label="Baseline length tolerance", unit="m", minimum=0.0, min_exclusive=True,
        maximum=10.0, decimals=3, step=0.005,
        help="an antenna whose measured distances to the others disagree with the known "
             "geometry by more than this is dropped for that epoch")
    sigma_horizontal_m: float = param(
        0.006, label="A-priori σ horizontal", unit="m", minimum=0.0, min_exclusive=True,
        maximum=10.0, decimals=4, step=0.001,
        help="per-antenna horizontal position noise (1σ) for the precision prediction and "
             "for weights = apriori (Liu et al.: about 0.6 cm)")
    sigma_vertical_m: float = param(
        0.012, label="A-priori σ vertical", unit="m", minimum=0.0, min_exclusive=True,
        maximum=10.0, decimals=4, step=0.001,
        help="per-antenna vertical position noise (1σ) for the precision prediction and "
             "for weights = apriori")
    weights: str = param(
        "file", label="Weights", choices=WEIGHTS,
        help="position covariance of each antenna: file = the std columns of the .pos files "
             "(a-priori σ when absent), apriori = the a-priori σ above")
    convergence_deg: float = param(
        1e-7, label="Convergence threshold", unit="°", minimum=0.0, min_exclusive=True,
        maximum=1.0, decimals=9, advanced=True,
        help="the least-squares iteration stops when every angle correction is below this")
    max_iterations: int = param(
        20, label="Maximum iterations", minimum=1, maximum=200, advanced=True,
        help="least-squares iterations per epoch before it is flagged not converged")
    direct_antennas: str = param(
        "", label="Direct-method antennas", advanced=True,
        help="three antenna names 'A1,A2,A3' for the direct method (A1→A2 the first "
             "baseline); empty = the largest triangle among the antennas available")
    epoch_rounding_s: float = param(
        0.01, label="Epoch matching", unit="s", minimum=0.0, min_exclusive=True,
        maximum=1.0, decimals=3, advanced=True,
        help="times of the antenna files are rounded to this before epochs are matched")
    gap_factor: float = param(
        1.5, label="Gap factor", minimum=1.0, maximum=100.0, decimals=1, advanced=True,
        help="an interval longer than this many median intervals between solved epochs "
             "counts as a gap")
    static_start_s: float | None = param(
        None, label="Static interval start", unit="s", none_label="first epoch",
        help="start (time of week) of the interval whose scatter gives the statistics table")
    static_end_s: float | None = param(
        None, label="Static interval end", unit="s", none_label="last epoch",
        help="end (time of week) of the statistics interval")

    def validate(self) -> None:
        if (self.static_start_s is not None and self.static_end_s is not None
                and not self.static_end_s > self.static_start_s):
            raise InputError(None, "the static interval must end after it starts",
                             field="static_end_s")
        names = [n.strip() for n in self.direct_antennas.split(",") if n.strip()]
        if names and (len(names) != 3 or len(set(names)) != 3):
            raise InputError(None, "give three different antenna names, e.g. 'A1,A2,A3'",
                             field="direct_antennas")

    @property
    def direct_triplet(self) -> tuple[str, str, str] | None:
        names = [n.strip() for n in self.direct_antennas.split(",") if n.strip()]
        return (names[0], names[1], names[2]) if names else None
