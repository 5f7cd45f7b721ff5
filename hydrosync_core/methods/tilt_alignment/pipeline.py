"""From an IMU record and GNSS antenna positions to the tip by every method.

Frames: NED (m) inside, body x forward, y right, z down along the pole towards the tip.
:func:`solve_record` runs Li et al.'s chain — Mahony levelling, observation vectors,
screening, BGD/SGD/MBGD, SVD — the closed-form heading-only least squares and the joint
batch least-squares, and returns one :class:`MethodResult` per method.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from hydrosync_core.errors import InputError
from hydrosync_core.methods.tilt_alignment import align
from hydrosync_core.methods.tilt_alignment.align import Undetermined, Vectors
from hydrosync_core.methods.tilt_alignment.geometry import (
    interpolate_vectors,
    mahony,
    pole_vectors,
    rz,
    tilt_of,
    wrap,
    yaw_of,
)
from hydrosync_core.methods.tilt_alignment.imu_convention import (
    DEFAULT as DEFAULT_CONVENTION,
)
from hydrosync_core.methods.tilt_alignment.imu_convention import mismatch_hint, to_model_grid
from hydrosync_core.methods.tilt_alignment.joint import JointResult, joint_lsq, white_sigma
from hydrosync_core.methods.tilt_alignment.params import HEADING_ONLY, METHODS, TiltParams
from hydrosync_core.progress import check_cancel, report

STANDARD_GRAVITY = 9.80665
#: smallest GNSS↔IMU time offset (s) the joint method corrects (when also > 3σ)
TIME_OFFSET_MIN_S = 0.002
#: a tip is flagged as weaker than the tolerance when the horizontal circle holding it with
#: this probability is wider, i.e. when the honest σ gives the tip more than a 5 % chance of
#: lying beyond the tolerance (95 %: the confidence level survey standards such as IHO S-44
#: state). Issue #30's rule — a swing without the warning is within 1 cm, and at most a
#: fifth of the tips within 1 cm are warned — then holds for MEMS and industrial IMUs (0 %
#: warned) and sits at its bound for consumer ones (20-22 %, as their own σ predict: 18 %;
#: at 99 % it flagged 47 %: their σ really is about 3 mm, and the 99 % circle of 3 mm is
#: 9-10 mm); on 460 swings of the three grades no tip without the warning was beyond 1 cm
#: (docs/benchmarks.md).
WARN_PROBABILITY = 0.95


@dataclass
class MethodResult:
    """One method's answer (NED, m; radians).

    ``psi`` is the heading misalignment (C = Rz(ψ)·C' at the start of the record), ``C0``
    the attitude estimated at the first IMU sample, ``tip``/``tip_std`` the tip and its
    1σ, ``history`` the gradient-descent iterates of ψ (empty for other methods).
    ``undetermined`` holds the reason when the data do not determine the result;
    ``warning`` says when the result is determined but weaker than the tip tolerance.
    """

    name: str
    psi: float = float("nan")
    psi_std: float = float("nan")
    C0: np.ndarray | None = None
    tip: np.ndarray = field(default_factory=lambda: np.full(3, np.nan))
    tip_std: np.ndarray = field(default_factory=lambda: np.full(3, np.nan))
    iterations: int = 0
    converged: bool = True
    history: np.ndarray = field(default_factory=lambda: np.zeros(0))
    vectors: int = 0
    undetermined: str | None = None
    warning: str | None = None

    @property
    def ok(self) -> bool:
        return self.undetermined is None


@dataclass
class TiltSolution:
    """Everything :func:`solve_record` found (NED, m; radians)."""

    methods: dict[str, MethodResult]
    vectors: Vectors
    screening: str | None            # why the vector set was refused, None when accepted
    C_imu: np.ndarray                # (N, 3, 3) levelled IMU attitude, heading 0 at start
    gnss_time: np.ndarray
    gnss_ned: np.ndarray
    epoch_tilt: np.ndarray           # (M,) rad, from the best available attitude
    tip_window: np.ndarray           # (M,) bool, epochs of the shot (heading-only tips)
    joint: JointResult | None
    gravity: float
    warnings: list[str] = field(default_factory=list)
    time: np.ndarray | None = None   # (N,) model times of C_imu and joint.C (s)
    imu_convention: str = DEFAULT_CONVENTION


@dataclass
class _Record:
    """The record on the model grid, levelled, with the attitude at the GNSS epochs."""

    time: np.ndarray
    gyro: np.ndarray
    accel: np.ndarray
    gnss_time: np.ndarray
    gnss_ned: np.ndarray
    length: float
    g: float
    C_imu: np.ndarray
    C_ep: np.ndarray
    window: np.ndarray
    gyro_noise: float        # per-row white noise of the rows as recorded (rad/s, m/s²):
    accel_noise: float       # the model grid's averaged rows would understate it
    instant: bool = False    # instantaneous accelerometer rows (else interval means)


def _heading_only(name: str, R: np.ndarray, C_epochs: np.ndarray, C_imu0: np.ndarray,
                  p: np.ndarray, window: np.ndarray, length: float, sigma_h: float,
                  sigma_v: float, psi_std: float, tilt_std: float) -> MethodResult:
    """Tip of a heading-only method: mean of the compensated shot epochs.

    σ: GNSS noise of the mean, the heading error (eq. 17) and the tilt error of the
    levelled attitude at the shot, *tilt_std* (rad, per horizontal axis: accelerometer
    bias during levelling and gyro-bias drift since), which moves the tip by ``l·δ``
    horizontally and ``l·sin β·δ`` vertically.
    """
    C = np.einsum("ij,kjl->kil", R, C_epochs)
    tips = align.compensate(p, C, length)[window]
    n = max(int(window.sum()), 1)
    beta = float(np.mean(tilt_of(C[window])))
    sh = math.hypot(sigma_h / math.sqrt(n), psi_std * length * math.sin(beta) / math.sqrt(2),
                    length * tilt_std)
    sv = math.hypot(sigma_v / math.sqrt(n), length * math.sin(beta) * tilt_std)
    return MethodResult(name, float(wrap(yaw_of(R))), psi_std, R @ C_imu0, tips.mean(axis=0),
                        np.array([sh, sh, sv]))


def weak_tip_warning(joint: JointResult, tolerance_m: float) -> str | None:
    """The warning for a tip weaker than *tolerance_m*, else None.

    Rule: the horizontal circle holding the tip with probability :data:`WARN_PROBABILITY`
    (from the tip's 2×2 covariance, both directions) is wider than the tolerance. The
    weakest horizontal direction of the tip is, for a swing nearly in one plane, across
    the plane: there the accelerometer bias along the swing axis and the tilt out of the
    plane are one unknown, fixed only by the bias prior (``bias_share``).
    """
    r = joint.horizontal_radius_m(WARN_PROBABILITY)
    if not math.isfinite(r) or r <= tolerance_m:
        return None
    d = joint.weak_direction
    az = math.degrees(math.atan2(d[1], d[0])) % 180.0
    head = (f"joint: the tip is uncertain to {1000 * r:.0f} mm horizontally at "
            f"{100 * WARN_PROBABILITY:.0f} % (±{1000 * 1.96 * joint.weak_sigma_m:.0f} mm "
            f"along azimuth {az:.0f}°/{az + 180:.0f}°), beyond the "
            f"{1000 * tolerance_m:.0f} mm tolerance")
    if joint.bias_share >= 0.5:
        return (f"{head}; the accelerometer bias, which this swing cannot tell from the "
                "tilt out of its plane (a swing nearly in one plane), makes "
                f"{100 * joint.bias_share:.0f} % of that variance: swing in an ellipse or "
                "twist the pole while swinging")
    return f"{head} (GNSS noise): swing wider or longer"


#: the IMU noise used is at least this share of the grade's (a noise-free record would
#: otherwise weight the model's second-order interpolation error of ``Δt²/8·ω̈`` as exact)
NOISE_FLOOR_SHARE = 0.05


def _noise_levels(time: np.ndarray, gyro: np.ndarray, accel: np.ndarray, p: TiltParams
                  ) -> tuple[float, float]:
    """Per-row white noise of the gyros (rad/s) and accelerometers (m/s²) as recorded
    (fifth differences, :func:`.joint.white_sigma`), floored at
    :data:`NOISE_FLOOR_SHARE` of the grade's; the grade's when the record is too short."""
    rate = 1.0 / float(np.median(np.diff(time)))
    grade = p.grade
    out = []
    for x, density in ((gyro, math.radians(grade.gyro_noise_deg_s_rthz)),
                       (accel, grade.accel_noise_m_s2_rthz)):
        nominal = density * math.sqrt(rate)
        v = white_sigma(x)
        out.append(max(v, NOISE_FLOOR_SHARE * nominal) if math.isfinite(v) else nominal)
    return out[0], out[1]


def _prepare(time, gyro, accel, gnss_time, gnss_ned, length, p: TiltParams, g: float,
             convention: str) -> _Record:
    """Model grid (:func:`.imu_convention.to_model_grid`), GNSS epochs inside the record,
    Mahony levelling and the levelled attitude at the epochs."""
    noise = _noise_levels(time, gyro, accel, p)
    time, gyro, accel = to_model_grid(time, gyro, accel, convention)
    inside = (gnss_time >= time[0]) & (gnss_time <= time[-1])
    gnss_time, gnss_ned = gnss_time[inside], gnss_ned[inside]
    if gnss_time.size < 5:
        raise InputError(None, f"only {gnss_time.size} GNSS epochs inside the IMU record "
                         "(at least 5 needed)", field="time")
    C_imu, _ = mahony(time, gyro, accel, p.level_s, p.mahony_kp, p.mahony_ki, g)
    u_imu, k, frac = interpolate_vectors(time, pole_vectors(C_imu, length), gnss_time)
    # attitude at the epochs: the nearer sample (only used for the tilt and the tips,
    # where 10 ms of rotation matter little); the pole vector itself is interpolated
    C_ep = np.where((frac < 0.5)[:, None, None], C_imu[k],
                    C_imu[np.minimum(k + 1, time.size - 1)]).copy()
    C_ep[:, :, 2] = u_imu / length
    window = gnss_time >= gnss_time[-1] - p.tip_window_s
    return _Record(time, gyro, accel, gnss_time, gnss_ned, length, g, C_imu, C_ep, window,
                   *noise, convention == "instant")


def _vector_sets(vec: Vectors) -> dict[str, np.ndarray]:
    """The vectors each heading-only method uses (SGD: the longest one only)."""
    allv = np.ones(len(vec.nav), bool)
    sets = {"bgd": allv, "mbgd": vec.used, "closed_form": vec.used, "svd": vec.used}
    if len(vec.nav):
        longest = np.zeros(len(vec.nav), bool)
        longest[int(np.argmax(np.linalg.norm(vec.nav, axis=1)))] = True
        sets["sgd"] = longest
    return sets


def _heading_only_methods(rec: _Record, vec: Vectors, screening: str | None,
                          p: TiltParams, cancel=None) -> dict[str, MethodResult]:
    """Li et al.'s BGD/SGD/MBGD and SVD and the closed form, each with its tip and σ."""
    eps = math.radians(p.stop_deg)
    sets = _vector_sets(vec)
    # tilt error of the levelled attitude at the shot (per horizontal axis, rad): the
    # accelerometer bias seen as tilt while levelling, the gyro bias integrated since
    drift_s = max(float(np.mean(rec.gnss_time[rec.window])) - (rec.time[0] + p.level_s), 0.0)
    tilt_std = math.hypot(p.accel_bias_prior_m_s2 / rec.g,
                          math.radians(p.gyro_bias_prior_deg_s) * drift_s)
    methods: dict[str, MethodResult] = {}
    for name in HEADING_ONLY:
        check_cancel(cancel)
        mask = sets.get(name)
        if mask is None or not mask.any():
            methods[name] = MethodResult(name, undetermined="no observation vector long "
                                         "enough: swing the pole wider")
            continue
        if screening is not None and name in ("mbgd", "svd", "closed_form"):
            methods[name] = MethodResult(name, undetermined=screening)
            continue
        methods[name] = _one_heading_method(name, rec, vec.nav[mask], vec.imu[mask],
                                            vec.centre, tilt_std, eps, p)
    return methods


def _one_heading_method(name: str, rec: _Record, nav: np.ndarray, imu: np.ndarray,
                        centre: float, tilt_std: float, eps: float, p: TiltParams
                        ) -> MethodResult:
    """One heading-only method on its vectors: ψ, its σ, the tip and the weak-tip warning."""
    d = None
    if name == "svd":
        R = align.wahba_svd(nav, imu)
        psi = yaw_of(R)
    elif name == "closed_form":
        psi = align.closed_form(nav, imu)
        R = rz(psi)
    else:
        d = align.descend(nav, imu, centre, p.learning_rate, eps, p.max_iterations)
        psi, R = d.psi, rz(d.psi)
    n_ep = rec.gnss_time.size
    psi_std = align.heading_sigma(nav, imu, psi, n_ep) if len(nav) > 1 else math.nan
    m = _heading_only(name, R, rec.C_ep, rec.C_imu[0], rec.gnss_ned, rec.window, rec.length,
                      p.sigma_h_m, p.sigma_v_m, psi_std if math.isfinite(psi_std) else 0.0,
                      tilt_std)
    m.psi_std, m.vectors = psi_std, len(nav)
    r_h = float(m.tip_std[0]) * math.sqrt(-2.0 * math.log(1.0 - WARN_PROBABILITY))
    if r_h > p.tip_tolerance_m:
        m.warning = (f"{name}: the tip is uncertain to {1000 * r_h:.0f} mm horizontally "
                     f"({100 * WARN_PROBABILITY:.0f} %), beyond the "
                     f"{1000 * p.tip_tolerance_m:.0f} mm tolerance: a heading-only method "
                     "keeps the levelling's tilt error (accelerometer bias, gyro drift "
                     "since); the joint method estimates it")
    if d is not None:
        m.iterations, m.converged, m.history = d.iterations, d.converged, d.history
        if not d.converged:
            m.undetermined = (f"gradient descent did not converge in {d.iterations} "
                              "iterations (learning rate or stop threshold)")
    return m


def _adjust_with_time_check(rec: _Record, C0: np.ndarray, tip0: np.ndarray, p: TiltParams,
                            cancel=None) -> JointResult:
    """The joint adjustment; a GNSS↔IMU offset the residuals show (> 3σ and
    > :data:`TIME_OFFSET_MIN_S`) is applied to the GNSS tags and the swing adjusted
    again (twice at most)."""
    def adjust(t_gnss, C_start, tip_start):
        return joint_lsq(rec.time, rec.gyro, rec.accel, t_gnss, rec.gnss_ned, rec.length,
                         C_start, tip_start, sigma_h=p.sigma_h_m, sigma_v=p.sigma_v_m,
                         g=rec.g, block_s=p.accel_block_s, gyro_noise=rec.gyro_noise,
                         accel_noise=rec.accel_noise,
                         gyro_bias_sigma=math.radians(p.gyro_bias_prior_deg_s),
                         accel_bias_sigma=p.accel_bias_prior_m_s2,
                         cancel_check=(lambda: check_cancel(cancel)),
                         accel_rows="instant" if rec.instant else "interval")

    joint = adjust(rec.gnss_time, C0, tip0)
    applied = 0.0
    for _ in range(2):
        tau, tau_sd = joint.time_offset_s, joint.time_offset_std_s
        if not (joint.converged and abs(tau) > max(3 * tau_sd, TIME_OFFSET_MIN_S)):
            break
        applied += tau
        joint = adjust(np.clip(rec.gnss_time + applied, rec.time[0], rec.time[-1]),
                       joint.C0, joint.tip)
    joint.time_offset_applied_s = applied
    return joint


#: the record's IMU noise beyond this multiple of its grade's is named (a wrong grade)
NOISE_WARN_FACTOR = 3.0


def grade_warning(rec: _Record, p: TiltParams) -> str | None:
    """A warning when the IMU is noisier than its declared grade allows."""
    rate = 1.0 / float(np.median(np.diff(rec.time)))
    grade = p.grade
    gyro = math.radians(grade.gyro_noise_deg_s_rthz) * math.sqrt(rate)
    accel = grade.accel_noise_m_s2_rthz * math.sqrt(rate)
    worse = [f"{name} {shown:.2g} {unit} per sample (a {p.imu_grade} IMU: {nominal:.2g})"
             for name, v, ref, shown, nominal, unit in (
                 ("gyro", rec.gyro_noise, gyro, math.degrees(rec.gyro_noise),
                  math.degrees(gyro), "°/s"),
                 ("accelerometer", rec.accel_noise, accel, rec.accel_noise, accel, "m/s²"))
             if v > NOISE_WARN_FACTOR * ref]
    if not worse:
        return None
    return (f"the IMU is noisier than its grade: {', '.join(worse)}; its bias priors may "
            "be too narrow as well (--imu-grade)")


def _joint_warnings(joint: JointResult, rec: _Record, convention: str) -> list[str]:
    """Down-weighted GNSS epochs, a corrected time offset and a likely convention
    mismatch."""
    out = []
    if joint.gnss_downweighted:
        out.append(f"joint: {joint.gnss_downweighted} GNSS epoch(s) far off the swing "
                   "(residual beyond twice the robust limit) were down-weighted: multipath "
                   "or a bad fix?")
    total = joint.time_offset_applied_s + joint.time_offset_s
    hint = mismatch_hint(total, joint.time_offset_std_s,
                         float(np.median(np.diff(rec.time))), convention)
    if hint:
        out.append(hint)
    elif joint.time_offset_applied_s:
        out.append(f"GNSS time tags are {1000 * joint.time_offset_applied_s:+.1f} ms (±"
                   f"{1000 * joint.time_offset_std_s:.1f}) off the IMU clock: corrected in "
                   "the joint solution (the other methods are not); check the receiver's "
                   "time alignment")
    return out


def _joint_method(rec: _Record, methods: dict[str, MethodResult], p: TiltParams,
                  convention: str, cancel=None
                  ) -> tuple[MethodResult, JointResult | None, list[str]]:
    """The joint batch least squares, started from the best heading-only answer."""
    start = next((methods[n] for n in ("closed_form", "bgd") if methods[n].ok), None)
    if start is None:
        return (MethodResult("joint", undetermined="no heading-only start value: "
                             + (methods["bgd"].undetermined or "")), None, [])
    C0 = rz(start.psi) @ rec.C_imu[0]
    tip0 = align.compensate(rec.gnss_ned, np.einsum("ij,kjl->kil", rz(start.psi), rec.C_ep),
                            rec.length).mean(axis=0)
    try:
        joint = _adjust_with_time_check(rec, C0, tip0, p, cancel)
    except np.linalg.LinAlgError as exc:
        return MethodResult("joint", undetermined=f"adjustment failed: {exc}"), None, []
    psi = float(wrap(yaw_of(joint.C0 @ rec.C_imu[0].T)))
    m = MethodResult("joint", psi, float(joint.attitude_std[2]), joint.C0, joint.tip,
                     joint.tip_std, joint.iterations, joint.converged,
                     vectors=int(rec.gnss_time.size))
    if not joint.converged:
        m.undetermined = "batch least squares did not converge"
    elif joint.sigma_gnss_m > 5 * p.sigma_h_m:
        m.undetermined = (f"GNSS positions do not fit a fixed tip (σ "
                          f"{100 * joint.sigma_gnss_m:.1f} cm): did the tip move?")
    else:
        m.warning = weak_tip_warning(joint, p.tip_tolerance_m)
    return m, joint, _joint_warnings(joint, rec, convention)


def _epoch_tilt(rec: _Record, best: MethodResult | None, joint: JointResult | None
                ) -> np.ndarray:
    """Tilt (rad) at the GNSS epochs from the best attitude available."""
    if best is not None and best.name == "joint" and joint is not None:
        u, _, _ = interpolate_vectors(rec.time, pole_vectors(joint.C, rec.length),
                                      rec.gnss_time)
        return np.arccos(np.clip(u[:, 2] / rec.length, -1, 1))
    return tilt_of(rec.C_ep)


def solve_record(time: np.ndarray, gyro: np.ndarray, accel: np.ndarray, gnss_time: np.ndarray,
                 gnss_ned: np.ndarray, length: float, params: TiltParams,
                 gravity: float | None = None, progress=None, cancel=None,
                 imu_convention: str | None = None) -> TiltSolution:
    """Solve one record by every method.

    Parameters
    ----------
    time : (N,) IMU time tags (s, increasing). gyro : (N, 3) rad/s. accel : (N, 3) m/s² —
    body frame (x forward, y right, z down along the pole). gnss_time : (M,) s, inside the
    IMU span. gnss_ned : (M, 3) antenna NED (m). length : antenna-to-tip distance (m).
    gravity : m/s² (None: ``params.gravity_m_s2`` or 9.80665).
    imu_convention : what an IMU row is (:mod:`.imu_convention`); ``params.imu_convention``
    wins when set; None for both: the data set's declaration is missing, ``instant``.

    Raises
    ------
    InputError
        Fewer than 5 GNSS epochs inside the IMU record.
    """
    p = params
    g = gravity if gravity is not None else (p.gravity_m_s2 or STANDARD_GRAVITY)
    convention = p.imu_convention or imu_convention or DEFAULT_CONVENTION
    check_cancel(cancel)
    rec = _prepare(np.asarray(time, float), gyro, accel, gnss_time, gnss_ned, length, p, g,
                   convention)
    report(progress, 0.1, "IMU levelled (Mahony)")
    u_imu, _, _ = interpolate_vectors(rec.time, pole_vectors(rec.C_imu, length),
                                      rec.gnss_time)
    vec = align.observation_vectors(rec.gnss_ned, u_imu, p.min_vector_m)
    screening = None
    try:
        align.screen(vec, p.reject_k, math.radians(p.reject_floor_deg),
                     math.radians(p.max_spread_deg), p.min_vectors)
    except Undetermined as exc:
        screening = str(exc)
    methods = _heading_only_methods(rec, vec, screening, p, cancel)
    report(progress, 0.3, "heading-only solutions")
    methods["joint"], joint, warnings = _joint_method(rec, methods, p, convention, cancel)
    noisy = grade_warning(rec, p)
    if noisy:
        warnings.append(noisy)
    report(progress, 0.9, "joint batch least squares")
    best = next((methods[n] for n in ("joint", "closed_form", "bgd") if methods[n].ok), None)
    tilt = _epoch_tilt(rec, best, joint)
    if screening is not None:
        warnings.append(f"vector screening: {screening}")
    if methods[p.method].warning:
        warnings.append(methods[p.method].warning)
    return TiltSolution({n: methods[n] for n in METHODS}, vec, screening, rec.C_imu,
                        rec.gnss_time, rec.gnss_ned, tilt, rec.window, joint, g, warnings,
                        rec.time, convention)
