"""Result dataclasses of the pool calibration; all serialise with ``to_dict`` (JSON).

Angles in degrees and lengths in metres at this edge; boresight and lever arm in the
``setup.json`` convention (boresight roll/pitch/yaw of R_m = Rz·Ry·Rx, lever arm body FRD).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field

import numpy as np

from hydrosync_core.jsonsafe import jsonable
from hydrosync_core.numfmt import value_sigma

# Decimals without a σ (an undetermined parameter): angles to the millidegree, lever arms
# to the tenth of a millimetre.
ANGLE_DECIMALS = 3
LEVER_DECIMALS = 4


def parameter_text(value, sigma, unit: str, sign: bool = False) -> str:
    """One final parameter as printed everywhere (CLI, panel, PDF): value and σ to the
    digits σ supports (:func:`~hydrosync_core.numfmt.value_sigma`); without a σ (not
    determined) the value to 0.001° / 0.1 mm."""
    s = None if sigma is None or not np.isfinite(float(sigma)) else float(sigma)
    return value_sigma(value, s, unit, decimals=None if s is not None else
                       (ANGLE_DECIMALS if unit == "\u00b0" else LEVER_DECIMALS), sign=sign)


@dataclass(frozen=True)
class FaceRow:
    face: str
    role: str
    water: str
    points_laser: int
    points_mbes: int
    rms_laser_m: float
    rms_mbes_m: float
    normal_angle_deg: float
    used_for: str
    #: Reference plane: "own" (crossing face: its own laser plane), the above-water twin's
    #: name (its laser plane moved by the design translation), or "" (none).
    reference: str = ""
    #: Design translation twin -> face (ENU, m); zeros for "own", NaN without reference.
    design_offset_m: tuple = (float("nan"),) * 3
    #: Which rule gave the reference plane ("own", "declared", "coplanar", "parallel
    #: offset") or why the face has none (:mod:`.twins`).
    pairing: str = ""


@dataclass(frozen=True)
class SeedSolution:
    """Seed (patent) solution: angle iteration then steps 4.1-4.4."""

    boresight_deg: dict
    lever_arm_m: dict
    iterations: int
    converged: bool
    lever_shift_enu_m: list
    undetermined: list


@dataclass(frozen=True)
class JointSolution:
    """Joint least-squares solution with 1-σ and correlations (order ``parameters``)."""

    boresight_deg: dict
    lever_arm_m: dict
    sigma_boresight_deg: dict
    sigma_lever_arm_m: dict
    parameters: list
    correlation: list
    sigma0_m: float
    n_observations: int
    iterations: int
    converged: bool
    undetermined: list
    residual_rms_m: dict
    #: Variance factor (>= 1) applied to each parameter's formal variance by the ping-block
    #: sandwich check (angles: about the body axes), see ``joint.py``.
    variance_factor: dict = field(default_factory=dict)
    #: Undetermined parameter -> reason (held at its coarse value, σ NaN).
    undetermined_reasons: dict = field(default_factory=dict)
    #: σ budget: source (data, build, reference, ins, held) -> parameter -> 1-σ from that
    #: source alone (° / m; null for undetermined parameters); the squares add up to σ².
    sigma_budget: dict = field(default_factory=dict)


@dataclass(frozen=True)
class PoolResult:
    """Final values (joint solution when available, else seed), with both solutions."""

    boresight_deg: dict
    lever_arm_m: dict
    iterations: int
    converged: bool
    message: str
    method: str
    coarse: dict
    seed: SeedSolution
    joint: JointSolution | None
    faces: list[FaceRow]
    iteration_table: list[dict]
    warnings: list[str] = field(default_factory=list)
    dropped_pings: int = 0
    dropped_soundings: int = 0
    #: Parameters of the final solution not determined by the data -> reason; their final
    #: value is the coarse one and their σ is NaN (CLI exit code 3).
    undetermined: dict = field(default_factory=dict)
    #: Parameters whose σ exceeds the warning threshold -> message.
    flagged: dict = field(default_factory=dict)
    #: Build tolerance of the twins used in the σ (half-widths, m and deg).
    build_tolerance: dict = field(default_factory=dict)
    #: Parameters whose correction exceeds the coarse accuracy -> message (also in
    #: ``flagged``): the data contradict the setup; not a calibration (CLI exit code 3).
    contradicted: dict = field(default_factory=dict)
    #: One entry per pass adjusted jointly: ``pass`` (1-based), ``pings``, ``soundings``
    #: (georeferenced) and ``on_faces`` (soundings on a face with a reference plane).
    passes: list = field(default_factory=list)

    def to_dict(self) -> dict:
        """JSON-ready dict (NaN -> null)."""
        return jsonable(asdict(self))
