"""Parameters of the pool calibration: the one place they are declared.

The panel form, the ``hydrosync pool-calibrate`` flags, ``hydrosync run pool_calibration
--param``, the stored parameters and the report's parameter table all derive from
:class:`PoolParams` (``hydrosync_core.params``). Imports only the standard library.

Schema history: version 1 stored the INS accuracy as three keys
``ins_sigma_roll_deg``/``ins_sigma_pitch_deg``/``ins_sigma_heading_deg``; version 2 holds
them in one triple ``ins_sigma_deg`` (:meth:`PoolParams.migrate`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from hydrosync_core.params import Params, param

SEG = "Segmentation"
SOLVE = "Iteration and adjustment"


@dataclass(frozen=True)
class PoolParams(Params):
    """Parameters of the pool calibration (patent CN 105425246 B and the joint adjustment).

    Lengths in metres, angles in degrees, times in seconds; frames as in
    ``docs/formats.md`` (target ENU, body x forward / y starboard / z down).
    """

    SCHEMA_VERSION: ClassVar[int] = 2

    final: str = param(
        "joint", label="Final values", choices=("joint", "seed"),
        help="final values from the joint least-squares adjustment (with σ) or from the "
             "patent's iteration")
    ins_sigma_deg: tuple[float, float, float] = param(
        (0.0, 0.0, 0.0), label="INS accuracy (1σ)", unit="°", minimum=0.0, maximum=5.0,
        decimals=4, step=0.001, cli="--ins-sigma", metavar=("ROLL", "PITCH", "HEADING"),
        help="INS roll, pitch and heading accuracy from its specification, propagated into "
             "the σ of the result (0: the INS is taken as exact and σ are a lower bound)")
    ins_tau_s: float = param(
        1.0, label="INS error correlation time", unit="s", minimum=0.0, min_exclusive=True,
        maximum=3600.0, cli="--ins-tau", decimals=2,
        help="Gauss–Markov correlation time of the INS attitude errors")
    build_tol_m: float = param(
        0.002, label="Build tolerance (position)", unit="m", minimum=0.0, maximum=1.0,
        decimals=4, step=0.0005,
        help="how well a below-water block is placed relative to its above-water twin "
             "(± per axis, half-width; σ = tol/√3): the design translation between twins is "
             "known only to this, and it is propagated into the σ of the result")
    build_tol_deg: float = param(
        0.01, label="Build tolerance (orientation)", unit="°", minimum=0.0, maximum=10.0,
        decimals=4, step=0.005,
        help="how well a below-water block is oriented relative to its above-water twin "
             "(± per axis, half-width; σ = tol/√3), propagated into the σ of the result")
    coarse_tol_deg: float = param(
        2.0, label="Coarse setup accuracy (angles)", unit="°", minimum=0.0,
        min_exclusive=True, maximum=90.0, decimals=2, group=SOLVE,
        help="± accuracy of the coarse boresight (installation drawing); an angle the data "
             "determine no better than this is undetermined and keeps its coarse value")
    coarse_tol_m: float = param(
        0.15, label="Coarse setup accuracy (lever arm)", unit="m", minimum=0.0,
        min_exclusive=True, maximum=100.0, decimals=3, group=SOLVE,
        help="± accuracy of the coarse lever arm; a component the data determine no better "
             "than this is undetermined and keeps its coarse value")
    crop_tol_m: float = param(
        0.6, label="Crop tolerance", unit="m", minimum=0.01, maximum=5.0, group=SEG,
        help="how far from the design faces soundings are first looked for (halved twice "
             "while the coarse setup is aligned); at least the error of the coarse setup "
             "at the target")
    min_points: int = param(
        30, label="Min points per face", minimum=3, maximum=1_000_000, group=SEG,
        help="faces with fewer points in either cloud are not used")
    min_soundings: int = param(
        10, label="Min soundings per face (joint)", minimum=3, maximum=1_000_000, group=SEG,
        advanced=True,
        help="the joint adjustment uses a face with at least this many soundings: each is "
             "one observation against the face's laser reference plane (no plane is fitted "
             "to them), so a small top seen at a grazing angle still fixes the vertical "
             "lever arm")
    tol_deg: float = param(
        1e-4, label="Angle tolerance", unit="°", minimum=0.0, min_exclusive=True,
        maximum=1.0, decimals=7, step=1e-5, group=SOLVE,
        help="the patent's iteration stops when every angle correction is below this")
    max_iter: int = param(
        30, label="Max iterations / round", minimum=1, maximum=1000, group=SOLVE,
        help="angle iterations per round at most")
    max_rounds: int = param(
        6, label="Max rounds", minimum=1, maximum=100, group=SOLVE,
        help="angle iteration + lever-arm step repeated at most this often")
    lever_tol_m: float = param(
        1e-4, label="Lever-arm tolerance", unit="m", minimum=0.0, min_exclusive=True,
        maximum=1.0, decimals=5, group=SOLVE, advanced=True,
        help="rounds stop when the lever arm changes less than this")
    huber_m: float = param(
        0.03, label="Huber threshold", unit="m", minimum=0.0, min_exclusive=True,
        maximum=10.0, group=SOLVE, advanced=True,
        help="point-to-plane residuals beyond this are down-weighted (robust adjustment)")
    sigma_block_s: float = param(
        2.0, label="σ ping block", unit="s", minimum=0.0, min_exclusive=True,
        maximum=600.0, decimals=1, group=SOLVE, advanced=True,
        help="ping-time block of the cluster-robust check that inflates σ when residuals "
             "of neighbouring soundings are correlated")
    max_sigma_deg: float = param(
        0.01, label="Flag above σ (angles)", unit="°", minimum=0.0, min_exclusive=True,
        maximum=10.0, decimals=4, group=SOLVE, advanced=True,
        help="an angle whose σ exceeds this is flagged as poorly determined (default: half "
             "an accuracy target of 0.02°, so an unflagged angle meets it at about 2σ)")
    max_sigma_m: float = param(
        0.001, label="Flag above σ (lever arm)", unit="m", minimum=0.0, min_exclusive=True,
        maximum=10.0, decimals=4, group=SOLVE, advanced=True,
        help="a lever-arm component whose σ exceeds this is flagged as poorly determined "
             "(default: half an accuracy target of 2 mm)")
    max_corr: float = param(
        0.9, label="Warn above |correlation|", minimum=0.0, maximum=1.0, group=SOLVE,
        advanced=True, help="pairs of parameters more correlated than this are flagged")
    laser_tol_m: float = param(
        0.3, label="Laser crop tolerance", unit="m", minimum=0.01, maximum=5.0, group=SEG,
        advanced=True, help="how far from the design faces laser points are kept")
    refine_tol_m: float = param(
        0.1, label="Re-crop tolerance", unit="m", minimum=0.001, maximum=5.0, group=SEG,
        advanced=True, help="crop tolerance around the faces once the first solution is known")
    refine_ransac_m: float = param(
        0.03, label="Re-crop RANSAC threshold", unit="m", minimum=0.001, maximum=5.0,
        group=SEG, advanced=True, help="plane inlier distance of the tight re-crop")
    refine_band_sigma: float = param(
        4.0, label="Band refit width", unit="σ", minimum=0.0, maximum=100.0, decimals=1,
        group=SEG, advanced=True,
        help="symmetric band (in robust σ) around each face's own plane kept by the refit "
             "(0: off)")
    face_margin_m: float = param(
        0.1, label="Face edge margin", unit="m", minimum=0.0, maximum=5.0, group=SEG,
        advanced=True, help="points this close to a face's edges are not used")
    water_margin_m: float = param(
        0.1, label="Water-line margin", unit="m", minimum=0.0, maximum=5.0, group=SEG,
        advanced=True, help="points this close to the water level are not used")
    ransac_laser_m: float = param(
        0.02, label="RANSAC threshold (laser)", unit="m", minimum=0.0005, maximum=5.0,
        decimals=4, group=SEG, advanced=True, help="plane inlier distance, laser points")
    ransac_mbes_m: float = param(
        0.1, label="RANSAC threshold (multibeam)", unit="m", minimum=0.001, maximum=5.0,
        group=SEG, advanced=True, help="plane inlier distance, soundings (coarse setup)")
    dbscan_laser_m: float = param(
        0.15, label="Cluster distance (laser)", unit="m", minimum=0.001, maximum=10.0,
        group=SEG, advanced=True, help="DBSCAN neighbourhood of the laser face clusters")
    dbscan_mbes_m: float = param(
        0.5, label="Cluster distance (multibeam)", unit="m", minimum=0.001, maximum=10.0,
        group=SEG, advanced=True, help="DBSCAN neighbourhood of the sounding face clusters")
    max_points_per_face: int = param(
        200_000, label="Max points per face", minimum=100, maximum=100_000_000, group=SEG,
        advanced=True, help="faces with more points are randomly thinned (seeded); every "
                            "sounding dropped widens the σ of the result, so the cap is only a "
                            "bound on memory (a four-pass session's wall holds about 150 000)")
    laser_voxel_m: float = param(
        0.02, label="Laser voxel size", unit="m", minimum=0.0, maximum=1.0, decimals=4,
        group=SEG, advanced=True, help="voxel down-sampling of very large laser clouds "
        "(0: off)")
    laser_voxel_above_points: int = param(
        2_000_000, label="Down-sample above", minimum=1000, maximum=1_000_000_000,
        group=SEG, advanced=True, help="laser clouds with more points are voxel down-sampled")
    max_gap_s: float | None = param(
        None, label="INS gap", unit="s", minimum=0.0, min_exclusive=True, maximum=3600.0,
        group=SEG, advanced=True, none_label="3 × the median INS interval",
        help="INS intervals longer than this are gaps: pings inside are dropped")
    plan_points: int = param(
        20000, label="Points kept for views", minimum=10, maximum=10_000_000, advanced=True,
        help="laser points and soundings stored for the plan views of panel and report")

    @classmethod
    def migrate(cls, values: dict, version: int) -> dict:
        values = dict(values)
        if version < 2:
            keys = [f"ins_sigma_{a}_deg" for a in ("roll", "pitch", "heading")]
            if any(k in values for k in keys):
                values["ins_sigma_deg"] = [values.pop(k, 0.0) or 0.0 for k in keys]
        return values
