"""Joint batch least-squares over the whole swing (HydroSync's addition to Li et al.).

Unknowns (12): the initial attitude ``C_0`` (a small rotation δθ applied in NED,
``C_0 ← Exp(δθ)·C_0``; heading included), the tip ``p_tip`` (NED, m), the gyro bias
``b_g`` (rad/s, body) and the accelerometer bias ``b_a`` (m/s², body).

Model: ``C_(k+1) = C_k·Exp((ω_k − b_g)·Δt_k)`` from the gyros; ``u_k = C_k·l_b`` (the pole
vector, antenna → tip, NED); the antenna ``p = p_tip − u``.

Observations:

* GNSS antenna positions: ``p_j = p_tip − u(t_j)`` (σ horizontal / vertical);
* accelerometers, in overlapping Hann windows ``w(t)`` (0.5 s, one every 0.25 s): the tip
  is fixed, so the antenna acceleration is ``a = −C·(α× + ω×ω×)·l_b = −d²u/dt²``, and
  integrating twice by parts ``∫ w·(C·(f − b_a) + g·e_down) dt = −∫ w''·u dt`` (the
  window and its slope vanish at both ends). Only the pole vector u enters, not its rate:
  an earlier form compared velocity increments with block-boundary velocities from central
  differences of u, whose gyro white noise (``l·σ_ω/√2`` per boundary, ≈ 4 mm/s for a
  consumer gyro on a 2 m pole) was 3-4 times the accelerometer's own noise and drowned the
  information. Discrete form: summation by parts on the sample grid, exact for the
  simulator's second differences. These observe roll and pitch at every sample — not only
  at a still moment.

Gauss-Newton with analytic Jacobians: a perturbation φ_k (NED) of the attitude at sample
k is ``φ_k = δθ − M_k·δb_g`` with ``M_k = Σ_(j<k) C_(j+1)·Δt_j``; ``δu_k = φ_k × u_k``.
Generalised least squares: the gyro white noise, integrated by the attitude, is a random
walk common to all later observations; it enters their covariance (not only white
weights), with the GNSS and accelerometer white noise. The IMU noise levels come from the
record itself (fifth differences); the four scale factors (GNSS horizontal, vertical,
accelerometer, gyro) are re-estimated from the residuals (variance components), and the
covariance of the result gives σ of the tip.

Observability: a swing in one vertical plane rotates the IMU about one horizontal axis
only, so the accelerometer bias along that axis stays the same vector in NED and looks
exactly like a tilt out of the plane (error ``b/g`` rad, ``l·b/g`` at the tip); only the
GNSS curvature term ``l·δθ·(1 − cos β)`` tells them apart, which is weak below about 40°.
The solution then rests on the bias prior. :func:`joint_lsq` measures how much: the
share of the tip's horizontal variance, along its weakest direction, that would vanish
if the accelerometer bias were known (``bias_share``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from hydrosync_core.methods.tilt_alignment.geometry import E_DOWN, exp_so3, propagate, skew

NPAR = 12
#: Huber threshold on a GNSS epoch's standardised 3-D residual (√χ²₃ at 99 %)
HUBER_K = 3.37
TH, TIP, BG, BA = slice(0, 3), slice(3, 6), slice(6, 9), slice(9, 12)


@dataclass
class JointResult:
    """Solution of :func:`joint_lsq` (NED, SI units, radians).

    ``bias_share``/``weak_direction``: see the module. ``time_offset_s`` ± ``_std_s``: the
    GNSS time tags' offset against the IMU clock indicated by the residuals (a check: the
    solution assumes the tags as given; :func:`.pipeline.solve_record` applies a significant
    offset to the tags, adjusts again and records it in ``time_offset_applied_s``).
    ``cov`` is the 12×12 covariance (δθ, tip, b_g, b_a); ``sigma_gnss_m`` and
    ``sigma_dv_m_s`` the a-posteriori σ of one horizontal GNSS coordinate and of one
    accelerometer window (m/s, its white noise); ``rms_gnss_m`` the RMS of the GNSS residuals;
    ``sigma_gnss_v_m`` the a-posteriori vertical GNSS σ; ``gyro_noise_rad_s`` and
    ``accel_noise_m_s2`` the per-sample white-noise σ of the IMU (from the record, scaled by
    their variance components); ``gnss_downweighted`` the GNSS epochs the robust (Huber)
    weights took to less than half their weight (residual beyond twice the threshold).
    """

    C0: np.ndarray
    tip: np.ndarray
    gyro_bias: np.ndarray
    accel_bias: np.ndarray
    cov: np.ndarray
    C: np.ndarray
    iterations: int
    converged: bool
    sigma_gnss_m: float
    sigma_dv_m_s: float
    rms_gnss_m: float
    gnss_residuals: np.ndarray
    n_blocks: int
    bias_share: float = 0.0
    weak_direction: np.ndarray | None = None
    time_offset_s: float = 0.0
    time_offset_std_s: float = float("nan")
    time_offset_applied_s: float = 0.0
    gyro_noise_rad_s: float = float("nan")
    accel_noise_m_s2: float = float("nan")
    sigma_gnss_v_m: float = float("nan")
    gnss_downweighted: int = 0

    @property
    def weak_sigma_m(self) -> float:
        """1σ (m) of the tip along its weakest horizontal direction."""
        d = self.weak_direction
        if d is None:
            return float("nan")
        return float(np.sqrt(max(d @ self.cov[3:5, 3:5] @ d, 0.0)))

    def horizontal_radius_m(self, probability: float) -> float:
        """Radius (m) of the horizontal circle about the estimate holding the tip with
        *probability* (from the 2×2 covariance, :func:`horizontal_radius`)."""
        return horizontal_radius(self.cov[3:5, 3:5], probability)

    @property
    def tip_std(self) -> np.ndarray:
        return np.sqrt(np.clip(np.diag(self.cov)[TIP], 0.0, None))

    @property
    def attitude_std(self) -> np.ndarray:
        """1σ (rad) of the initial attitude about north, east and down."""
        return np.sqrt(np.clip(np.diag(self.cov)[TH], 0.0, None))


def horizontal_radius(cov2: np.ndarray, probability: float) -> float:
    """Radius r with ``P(|e| ≤ r) = probability`` for a 2-D Gaussian error e ~ N(0, cov2).

    With eigenvalues λ_big ≥ λ_small, ``P(r) = ∫ φ(z)·erf(√((r² − λ_big·z²)/(2·λ_small)))
    dz`` over ``|z| ≤ r/√λ_big``; solved by bisection. For a circular error this is
    ``σ·√(−2·ln(1 − p))`` (3.03 σ at 99 %), for a thin one ``z_p·σ_max`` (2.58 σ at 99 %).
    """
    from scipy.special import erf

    lam = np.linalg.eigvalsh(np.asarray(cov2, float))
    if not np.all(np.isfinite(lam)):
        return float("nan")
    small, big = (max(float(v), 0.0) for v in lam)
    if big <= 0:
        return 0.0
    x = np.linspace(-1.0, 1.0, 2001)

    def cdf(r):
        z = x * r / math.sqrt(big)
        inner = np.clip(r * r - big * z * z, 0.0, None)
        term = erf(np.sqrt(inner / (2 * small))) if small > 0 else (inner > 0).astype(float)
        f = np.exp(-0.5 * z * z) / math.sqrt(2 * math.pi) * term
        return float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(z)))

    lo, hi = 0.0, 10.0 * math.sqrt(big + small)
    for _ in range(50):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if cdf(mid) < probability else (lo, mid)
    return 0.5 * (lo + hi)


def _windows(time: np.ndarray, block_s: float, overlap: bool = True
             ) -> tuple[np.ndarray, np.ndarray]:
    """Accelerometer windows as weight matrices ``(Wq, D)``, each (B, N).

    Window *i* is a Hann bump ``w = sin²(π·(t − t_a)/(t_b − t_a))`` over ``[t_a, t_b]``
    (twice *block_s* long, one every *block_s*: they overlap by half and sum to one);
    ``Wq[i, k] = q_k·w_k`` with the trapezoid weights ``q_k``, and ``D[i, k]`` the
    second divided difference of *w* — summation by parts of ``Σ q_k·w_k·a_k`` with
    ``a_k`` the second divided difference of the antenna position, so that
    ``Σ_k Wq·a = Σ_k D·p`` exactly for the discrete record and ``Σ_k D = 0``.
    """
    n = time.size
    if n < 6 or block_s <= 0:
        return np.zeros((0, n)), np.zeros((0, n))
    dt = float(np.median(np.diff(time)))
    step = max(2, int(round(block_s / dt)))
    span = 2 * step if overlap else step
    starts = np.arange(1, n - 1 - span, step)   # interior samples only (a ≥ 1, b ≤ n−2)
    h = np.diff(time)
    q = np.zeros(n)
    q[1:-1] = 0.5 * (h[:-1] + h[1:])
    Wq = np.zeros((starts.size, n))
    D = np.zeros((starts.size, n))
    for i, a in enumerate(starts):
        b = a + span
        w = np.zeros(n + 2)                             # w[k + 1] is sample k, 0 outside
        w[a + 1:b + 2] = np.sin(np.pi * (time[a:b + 1] - time[a]) / (time[b] - time[a])) ** 2
        Wq[i] = q * w[1:-1]
        k = np.arange(a, b + 1)
        D[i, k] = (w[k + 2] - w[k + 1]) / h[k] - (w[k + 1] - w[k]) / h[k - 1]
    return Wq, D


def numerov_weights(Wq: np.ndarray) -> np.ndarray:
    """Window weights for instantaneous accelerometer rows: ``Wq·N`` with N the filter
    ``(y_(k−1) + 10·y_k + y_(k+1))/12`` applied to the NED specific force ``y = C·f``.

    The windows compare ``Σ Wq·y`` with second differences of the antenna path, which
    equal the acceleration plus ``Δt²/12`` times its second derivative; N adds that term
    to instantaneous samples, in NED (in the body frame the pole's rotation would leave
    ``Δt²/12·C̈·f``, 5·10⁻³ m/s² on a fast swing at 50 Hz).
    """
    out = Wq * (10.0 / 12.0)
    out[:, :-1] += Wq[:, 1:] / 12.0
    out[:, 1:] += Wq[:, :-1] / 12.0
    return out


def interval_weights(Wq: np.ndarray) -> np.ndarray:
    """Window weights for interval-mean accelerometer rows (row *k* the mean over
    ``[t_k, t_(k+1))``, in NED, :func:`ned_force`):
    ``Wq·M`` with M the fourth-order map from interval means to the value the second
    differences see at ``t_k``, ``(13(Y_(k−1) + Y_k) − Y_(k−2) − Y_(k+1))/24``."""
    out = np.zeros_like(Wq)
    out[:, :-1] += 13.0 / 24.0 * Wq[:, 1:]
    out += 13.0 / 24.0 * Wq
    out[:, :-2] -= Wq[:, 2:] / 24.0
    out[:, 1:] -= Wq[:, :-1] / 24.0
    return out


def ned_force(C: np.ndarray, time: np.ndarray, accel: np.ndarray, gyro: np.ndarray | None,
              mid: bool) -> tuple[np.ndarray, np.ndarray]:
    """Accelerometer rows in NED, and the matrices that map a body-frame change of a row
    (a bias) into NED: ``(y (N, 3), A (N, 3, 3))``.

    Instantaneous rows: ``y_k = C_k·f_k``. Interval means (*mid*; *gyro* the rotation over
    the interval divided by its length): the NED mean over ``[t_k, t_(k+1))``,
    ``y_k = C_k·(f̄ + φ×f̄/2 + φ×(φ×f̄)/6 + Δt²/12·(ω̄×ḟ − ω̇×f̄))`` with ``φ = ω̄·Δt``,
    to third order in ``Ω·Δt``: the attitude turns inside the interval while the force
    changes (a sculling term). The mean of the two end attitudes, kept before, left
    ``Δt²/12·ω̄×ḟ`` and ``φ×(φ×f̄)/12``: 0.02 m/s² in a window of a fast swing at 50 Hz,
    three times the accelerometer noise (issue #30).
    """
    accel = np.asarray(accel, float)
    if not mid:
        return np.einsum("kij,kj->ki", C, accel), C
    dt = np.empty(time.size)
    dt[:-1] = np.diff(time)
    dt[-1] = dt[-2]
    phi = gyro * dt[:, None]
    half = np.cross(phi, accel) / 2.0
    body = accel + half + np.cross(phi, np.cross(phi, accel)) / 6.0
    body += dt[:, None] ** 2 / 12.0 * (np.cross(gyro, np.gradient(accel, time, axis=0))
                                       - np.cross(np.gradient(gyro, time, axis=0), accel))
    T = np.eye(3) + skew(phi) / 2.0
    return np.einsum("kij,kj->ki", C, body), C @ T


def _model(C, time, accel, gnss_t, length, tip, ba, g, windows, mid=False, gyro=None):
    """Residuals (GNSS (M,3), accelerometer windows (B,3)) and their Jacobians
    ((M,3,12), (B,3,12)); *gyro* (bias removed) for interval-mean rows (:func:`ned_force`)."""
    n = time.size
    dt = np.diff(time)
    u = C[:, :, 2] * length
    # φ_k = δθ − M_k δb_g
    M = np.zeros((n, 3, 3))
    M[1:] = np.cumsum(C[1:] * dt[:, None, None], axis=0)
    Phi = np.zeros((n, 3, NPAR))
    Phi[:, :, TH] = np.eye(3)
    Phi[:, :, BG] = -M
    Du = -skew(u) @ Phi                                   # ∂u_k/∂x
    # GNSS: e = p − tip + u(t_j)
    k = np.clip(np.searchsorted(time, gnss_t, side="right") - 1, 0, n - 2)
    f = ((gnss_t - time[k]) / dt[k])[:, None]
    u_at = u[k] * (1 - f) + u[k + 1] * f
    Dg = Du[k] * (1 - f)[:, :, None] + Du[k + 1] * f[:, :, None]
    Dg[:, :, TIP] -= np.eye(3)
    # accelerometers, window i: e = Σ_k Wq·(C(f − b_a) + g·e_d) + Σ_k D·u
    # (= ∫w·a dt − ∫w·ü dt with the antenna acceleration a = −ü: no velocities needed)
    Wq, D = windows
    y, A = ned_force(C, time, accel - ba, gyro, mid)
    Dy = -skew(y) @ Phi
    Dy[:, :, BA] -= A
    ea = Wq @ (y + g * E_DOWN) + D @ u
    Da = np.einsum("bk,kij->bij", Wq, Dy) + np.einsum("bk,kij->bij", D, Du)
    return u_at, Dg, ea, Da


#: order of the differences that measure an IMU record's white noise, and the variance of
#: that difference of unit white noise (``C(2n, n)``)
NOISE_DIFF_ORDER, NOISE_DIFF_GAIN = 5, 252.0


def white_sigma(x: np.ndarray) -> float:
    """Per-sample σ of the white noise on the columns of *x* (N, 3), from fifth
    differences (robust: MAD), RMS over the axes.

    ``Δ⁵`` of white noise has variance 252·σ²; a swing's smooth motion enters with
    ``(Ω·Δt)⁵`` times its amplitude. Third differences (``(Ω·Δt)³``) read a fast
    three-sweep swing at 50 Hz as 1.5× the accelerometer noise (issue #30); fifth
    differences as 1.05×.
    """
    d = np.diff(np.asarray(x, float), n=NOISE_DIFF_ORDER, axis=0)
    if d.shape[0] < 10:
        return float("nan")
    mad = np.median(np.abs(d - np.median(d, axis=0)), axis=0)
    return float(np.sqrt(np.mean((1.4826 * mad) ** 2 / NOISE_DIFF_GAIN)))


def _gyro_noise_design(C, time, gnss_t, u, y, windows, chunk):
    """``H`` (R, K·3): the observations' (GNSS rows, then windows) sensitivity to the gyro
    white noise, summed over chunks of *chunk* samples: ``Q = σ_ω²·H·Hᵀ``.

    Gyro noise ``n_j`` (body, rad/s) over ``[t_j, t_(j+1))`` turns every later attitude by
    ``φ_k = Σ_(j<k) C_(j+1)·Δt_j·n_j`` (NED); an observation with ``∂o/∂φ_k = G_k`` moves by
    ``Σ_j (Σ_(k>j) G_k)·C_(j+1)·Δt_j·n_j``; ``C`` is orthogonal, so the covariance needs
    only ``Σ_(k>j) G_k·Δt_j``. Noise within a chunk is treated as one increment.
    """
    n = time.size
    dt = np.diff(time)
    Wq, D = windows
    m = gnss_t.size
    k = np.clip(np.searchsorted(time, gnss_t, side="right") - 1, 0, n - 2)
    f = (gnss_t - time[k]) / dt[k]
    su, sy = skew(u), skew(y)
    G = np.zeros((3 * m + 3 * Wq.shape[0], n, 3))
    rows = np.arange(m)
    Gg = np.zeros((m, n, 3, 3))
    Gg[rows, k] = -su[k] * (1 - f)[:, None, None]
    Gg[rows, k + 1] += -su[k + 1] * f[:, None, None]
    G[:3 * m] = Gg.transpose(0, 2, 1, 3).reshape(3 * m, n, 3)
    if Wq.shape[0]:
        Gw = -(np.einsum("bk,kij->bikj", Wq, sy) + np.einsum("bk,kij->bikj", D, su))
        G[3 * m:] = Gw.reshape(-1, n, 3)
    # H_j = Σ_(k>j) G_k, for j = 0 … n−2
    H = np.cumsum(G[:, ::-1], axis=1)[:, ::-1][:, 1:] * dt[None, :, None]
    if chunk > 1:
        nc = (n - 1) // chunk
        Hc = H[:, :nc * chunk].reshape(H.shape[0], nc, chunk, 3).mean(axis=2) * math.sqrt(chunk)
        H = np.concatenate([Hc, H[:, nc * chunk:]], axis=1)
    return H.reshape(H.shape[0], -1)


@dataclass
class _Problem:
    """The fixed data of one adjustment and its covariance components (R × R)."""

    time: np.ndarray
    gyro: np.ndarray
    accel: np.ndarray
    gnss_t: np.ndarray
    gnss_p: np.ndarray
    length: float
    g: float
    windows: tuple[np.ndarray, np.ndarray]
    gyro_noise: float
    accel_noise: float
    chunk: int
    mid: bool                   # interval-mean accelerometer rows
    gyro_bias_sigma: float
    accel_bias_sigma: float
    Qh: np.ndarray              # diagonal, GNSS horizontal
    Qv: np.ndarray              # diagonal, GNSS vertical
    Qa: np.ndarray              # accelerometer windows

    @property
    def m(self) -> int:
        return self.gnss_t.size


@dataclass
class _State:
    """The unknowns and the attitudes they imply."""

    C0: np.ndarray
    tip: np.ndarray
    bg: np.ndarray
    ba: np.ndarray
    C: np.ndarray


def _problem(time, gyro, accel, gnss_t, gnss_p, length, g, block_s, sigma_h, sigma_v,
             gyro_noise, accel_noise, gyro_bias_sigma, accel_bias_sigma, accel_rows
             ) -> _Problem:
    """Windows, IMU noise levels (from the record when not given) and the fixed
    covariance components (GNSS horizontal and vertical, accelerometer windows)."""
    windows = _windows(time, block_s)
    if accel_rows == "instant":
        windows = (numerov_weights(windows[0]), windows[1])
    elif accel_rows == "interval":
        windows = (interval_weights(windows[0]), windows[1])
    Wq = windows[0]
    m, nb = gnss_t.size, Wq.shape[0]
    dt_med = float(np.median(np.diff(time)))
    sw = gyro_noise if gyro_noise is not None else white_sigma(gyro)
    sf = accel_noise if accel_noise is not None else white_sigma(accel)
    sw = sw if math.isfinite(sw) and sw > 0 else math.radians(0.01) / math.sqrt(dt_med)
    sf = sf if math.isfinite(sf) and sf > 0 else 0.001 / math.sqrt(dt_med)
    R = 3 * (m + nb)
    Qh, Qv = np.zeros(R), np.zeros(R)
    Qh[:3 * m] = np.tile([sigma_h ** 2, sigma_h ** 2, 0.0], m)
    Qv[:3 * m] = np.tile([0.0, 0.0, sigma_v ** 2], m)
    Qa = np.zeros((R, R))
    Qa[3 * m:, 3 * m:] = np.kron(Wq @ Wq.T, np.eye(3)) * sf ** 2
    return _Problem(time, gyro, accel, gnss_t, gnss_p, length, g, windows, sw, sf,
                    max(1, int(round(0.02 / dt_med))), accel_rows == "interval",
                    gyro_bias_sigma, accel_bias_sigma,
                    Qh, Qv, Qa)


def _prior_rows(pb: _Problem, st: _State) -> tuple[np.ndarray, np.ndarray]:
    """Whitened bias priors about zero: design (6, 12) and residuals (6,)."""
    P = np.zeros((6, NPAR))
    P[:3, BG] = np.eye(3) / pb.gyro_bias_sigma
    P[3:, BA] = np.eye(3) / pb.accel_bias_sigma
    return P, np.concatenate([st.bg / pb.gyro_bias_sigma, st.ba / pb.accel_bias_sigma])


def _linearise(pb: _Problem, st: _State) -> tuple[np.ndarray, np.ndarray]:
    """Residuals (GNSS rows, then windows) and their Jacobian at the state."""
    u_at, Dg, ea, Da = _model(st.C, pb.time, pb.accel, pb.gnss_t, pb.length, st.tip, st.ba,
                              pb.g, pb.windows, pb.mid, pb.gyro - st.bg)
    e = np.concatenate([(pb.gnss_p - st.tip + u_at).ravel(), ea.ravel()])
    return e, np.vstack([Dg.reshape(-1, NPAR), Da.reshape(-1, NPAR)])


def _gyro_cov(pb: _Problem, st: _State) -> np.ndarray:
    """The gyro-noise covariance component σ_ω²·H·Hᵀ at the state."""
    u = st.C[:, :, 2] * pb.length
    y, _ = ned_force(st.C, pb.time, pb.accel - st.ba, pb.gyro - st.bg, pb.mid)
    H = _gyro_noise_design(st.C, pb.time, pb.gnss_t, u, y, pb.windows, pb.chunk)
    return (H @ H.T) * pb.gyro_noise ** 2


def _whitened(pb: _Problem, st: _State, L: np.ndarray):
    """Whitened design and residuals, observations (by the Cholesky factor L) then priors."""
    from scipy.linalg import solve_triangular

    e, A = _linearise(pb, st)
    P, rp = _prior_rows(pb, st)
    Aw = np.vstack([solve_triangular(L, A, lower=True), P])
    rw = np.concatenate([solve_triangular(L, e, lower=True), rp])
    return Aw, rw


def _gauss_newton(pb: _Problem, st: _State, L: np.ndarray, max_iterations: int,
                  cancel_check) -> tuple[_State, int, bool]:
    """Gauss-Newton with a fixed covariance (Cholesky factor L) until the step is below
    10⁻¹⁰ rad, 10⁻⁸ m, 10⁻¹⁰ rad/s and 10⁻⁹ m/s²."""
    for it in range(1, max_iterations + 1):
        if cancel_check is not None:
            cancel_check()
        Aw, rw = _whitened(pb, st, L)
        dx, *_ = np.linalg.lstsq(Aw, -rw, rcond=None)
        C0 = exp_so3(dx[TH]) @ st.C0
        bg = st.bg + dx[BG]
        st = _State(C0, st.tip + dx[TIP], bg, st.ba + dx[BA],
                    propagate(C0, pb.time, pb.gyro, bg))
        if (np.linalg.norm(dx[TH]) < 1e-10 and np.linalg.norm(dx[TIP]) < 1e-8
                and np.linalg.norm(dx[BG]) < 1e-10 and np.linalg.norm(dx[BA]) < 1e-9):
            return st, it, True
    return st, max_iterations, False


def _variance_components(pb: _Problem, st: _State, Sigma: np.ndarray, comps: tuple,
                         theta: np.ndarray) -> np.ndarray:
    """Förstner's update ``θ_i ← θ_i·vᵀWΣ_iWv / tr(P·Σ_i)``, with ``P = W − W·A·N⁻¹·Aᵀ·W``,
    ``W = Σ⁻¹`` (the bias priors are observations without a component of their own),
    clipped to [1, 50²] for the GNSS and [1, 20²] for the IMU components."""
    from scipy.linalg import cho_factor, cho_solve

    e, A = _linearise(pb, st)
    Pr, rp = _prior_rows(pb, st)
    cf = cho_factor(Sigma, lower=True)
    We, WA = cho_solve(cf, e), cho_solve(cf, A)
    Ninv = np.linalg.pinv(A.T @ WA + Pr.T @ Pr)
    v = We - WA @ (Ninv @ (WA.T @ e + Pr.T @ rp))     # W·v at the solution
    Pm = cho_solve(cf, np.eye(Sigma.shape[0])) - WA @ Ninv @ WA.T
    new = theta.copy()
    for i, S in enumerate(comps):
        red_i = float(np.sum(Pm * S))                  # tr(P·Σ_i), Σ_i symmetric
        if red_i > 1.0:
            new[i] = theta[i] * float(v @ S @ v) / red_i
    # no σ may shrink below its a-priori value: a dozen epochs (2 Hz) estimate the GNSS σ
    # to ±20 %, and a receiver's stated RTK σ is a floor; the IMU noise is measured from
    # the record itself (fifth differences, to a few %); its components have little
    # redundancy in a swing, so they may grow (a model error) but not fall below the
    # measured noise (issue #30)
    return np.clip(new, 1.0, np.array([50.0, 50.0, 20.0, 20.0]) ** 2)


def _huber_inflation(pb: _Problem, st: _State, theta: np.ndarray) -> np.ndarray:
    """Variance inflation per observation row (1 = full weight): a GNSS epoch whose
    residual, standardised by the white GNSS σ, is beyond HUBER_K (χ²₃ 99 %) has its
    variance grow with the residual."""
    m = pb.m
    e, _ = _linearise(pb, st)
    sd = np.sqrt(theta[0] * pb.Qh[:3 * m] + theta[1] * pb.Qv[:3 * m]).reshape(m, 3)
    d = np.sqrt(np.sum((e[:3 * m].reshape(m, 3) / sd) ** 2, axis=1))
    infl = np.ones(pb.Qh.size)
    infl[:3 * m] = np.repeat(np.maximum(1.0, d / HUBER_K), 3)
    return infl


def _covariance(pb: _Problem, theta: np.ndarray, infl: np.ndarray, Qw: np.ndarray
                ) -> np.ndarray:
    """Σ = inflated GNSS components + θ_a·Q_a + θ_ω·Q_ω, with a 10⁻¹² relative jitter."""
    Sigma = (np.diag(infl * (theta[0] * pb.Qh + theta[1] * pb.Qv)) + theta[2] * pb.Qa
             + theta[3] * Qw)
    Sigma[np.diag_indices(Sigma.shape[0])] += 1e-12 * np.max(np.diag(Sigma))
    return Sigma


def joint_lsq(time: np.ndarray, gyro: np.ndarray, accel: np.ndarray, gnss_t: np.ndarray,
              gnss_p: np.ndarray, length: float, C0: np.ndarray, tip0: np.ndarray, *,
              sigma_h: float, sigma_v: float, g: float, block_s: float = 0.25,
              gyro_noise: float | None = None, accel_noise: float | None = None,
              gyro_bias_sigma: float = math.radians(0.05), accel_bias_sigma: float = 0.02,
              max_iterations: int = 30, vce_rounds: int = 4, cancel_check=None,
              accel_rows: str = "model") -> JointResult:
    """Estimate initial attitude, tip and IMU biases from the whole record.

    Generalised least squares: the observations' covariance holds the GNSS white noise
    (horizontal, vertical), the accelerometers' white noise through the overlapping
    windows, and the gyros' white noise, which the attitude integrates into a random walk
    common to every later observation (angle random walk: it correlates all of them and
    is the limit of what a short swing can tell). Its four scale factors are re-estimated
    from the residuals (variance components, Förstner's redundancy form), and each GNSS
    epoch gets a robust (Huber) weight from its standardised residual. The matrices are a
    few hundred rows: BLAS runs on one thread (several threads on a loaded two-core
    machine made it ten times slower).

    Parameters
    ----------
    time : (N,) IMU model times (s). gyro : (N, 3) rad/s, mean over ``[t_k, t_(k+1))``.
    accel : (N, 3) m/s² at ``t_k`` (body frame; :func:`.imu_convention.to_model_grid`).
    gnss_t : (M,) s. gnss_p : (M, 3) antenna NED (m). length : pole length (m).
    C0 : initial attitude guess (body→NED) at ``time[0]``. tip0 : tip guess (NED, m).
    sigma_h, sigma_v : a-priori GNSS σ (m). g : gravity (m/s²).
    gyro_noise, accel_noise : per-sample white-noise σ of the gyros (rad/s) and
    accelerometers (m/s²); None: from the record (:func:`white_sigma`).
    gyro_bias_sigma, accel_bias_sigma : a-priori 1σ of the biases about zero (rad/s,
    m/s², the IMU grade's bias stability): a swing in one plane cannot separate the
    accelerometer bias along the swing axis from the tilt out of that plane, so the
    prior bounds it.
    block_s : step of the accelerometer windows (s; each twice as long).
    vce_rounds : re-weighting rounds from the residuals.
    accel_rows : ``"instant"`` (samples at ``t_k``, :func:`numerov_weights`),
    ``"interval"`` (means over ``[t_k, t_(k+1))``, :func:`interval_weights`) or
    ``"model"`` (already as the second differences of the antenna path see them).
    """
    from threadpoolctl import threadpool_limits

    with threadpool_limits(limits=1, user_api="blas"):
        pb = _problem(time, gyro, accel, gnss_t, gnss_p, length, g, block_s, sigma_h,
                      sigma_v, gyro_noise, accel_noise, gyro_bias_sigma, accel_bias_sigma,
                      accel_rows)
        C0 = np.array(C0, float)
        st = _State(C0, np.array(tip0, float), np.zeros(3), np.zeros(3),
                    propagate(C0, time, gyro, np.zeros(3)))
        theta, infl = np.ones(4), np.ones(pb.Qh.size)
        Qw = _gyro_cov(pb, st)
        it_total, converged = 0, False
        for rnd in range(vce_rounds + 1):
            Sigma = _covariance(pb, theta, infl, Qw)
            L = np.linalg.cholesky(Sigma)
            st, its, converged = _gauss_newton(pb, st, L, max_iterations, cancel_check)
            it_total += its
            Qw = _gyro_cov(pb, st)
            if rnd == vce_rounds:
                break
            comps = (np.diag(infl * theta[0] * pb.Qh), np.diag(infl * theta[1] * pb.Qv),
                     theta[2] * pb.Qa, theta[3] * Qw)
            theta = _variance_components(pb, st, Sigma, comps, theta)
            infl = _huber_inflation(pb, st, theta)
        return _result(pb, st, L, theta, infl, it_total, converged, sigma_h, sigma_v)


def _result(pb: _Problem, st: _State, L: np.ndarray, theta: np.ndarray, infl: np.ndarray,
            iterations: int, converged: bool, sigma_h: float, sigma_v: float
            ) -> JointResult:
    """Covariance (scaled by the a-posteriori variance factor when above one), the weak
    direction, the time-offset check and the a-posteriori noise levels."""
    m, nb = pb.m, pb.windows[0].shape[0]
    Aw, rw = _whitened(pb, st, L)
    var_factor = max(float(rw @ rw) / max(L.shape[0] - NPAR, 1), 1.0)
    normal = Aw.T @ Aw
    cov = np.linalg.pinv(normal) * var_factor
    share, weak = _bias_share(normal, cov, var_factor, pb.accel_bias_sigma)
    # second-order check of the GNSS↔IMU time alignment: one Gauss-Newton step of the
    # solution augmented by a time offset τ (GNSS tag t_j is the pole at t_j + τ:
    # ∂e_j/∂τ = du/dt(t_j)), from the converged solution; the solution itself is kept
    tau, tau_std = _time_offset(Aw, rw, L, st.C, pb.time, pb.gnss_t, pb.length, var_factor)
    e, _ = _linearise(pb, st)
    eg = e[:3 * m].reshape(m, 3)
    s_window = float(np.sqrt(np.mean(np.diag(pb.Qa)[3 * m:]) * theta[2])) if nb else math.nan
    return JointResult(st.C0, st.tip, st.bg, st.ba, cov, st.C, iterations, converged,
                       sigma_h * math.sqrt(theta[0]), s_window,
                       float(np.sqrt(np.mean(eg ** 2))), eg, int(nb), share, weak, tau,
                       tau_std, gyro_noise_rad_s=pb.gyro_noise * math.sqrt(theta[3]),
                       accel_noise_m_s2=pb.accel_noise * math.sqrt(theta[2]),
                       sigma_gnss_v_m=sigma_v * math.sqrt(theta[1]),
                       gnss_downweighted=int(np.sum(infl[:3 * m:3] > 2.0)))


def _time_offset(Aw: np.ndarray, rw: np.ndarray, L: np.ndarray, C: np.ndarray,
                 time: np.ndarray, gnss_t: np.ndarray, length: float, var_factor: float
                 ) -> tuple[float, float]:
    """Time offset τ (s) of the GNSS tags against the IMU and its 1σ, from the whitened
    design *Aw* and residuals *rw* of the converged solution (observation rows whitened
    by the Cholesky factor *L*, GNSS rows first, then the prior rows)."""
    from scipy.linalg import solve_triangular

    u = C[:, :, 2] * length
    n = time.size
    k = np.clip(np.searchsorted(time, gnss_t, side="right") - 1, 0, n - 2)
    rate = (u[k + 1] - u[k]) / (time[k + 1] - time[k])[:, None]
    col = np.zeros(L.shape[0])
    col[:rate.size] = rate.ravel()
    colw = np.concatenate([solve_triangular(L, col, lower=True),
                           np.zeros(Aw.shape[0] - L.shape[0])])
    Aa = np.column_stack([Aw, colw])
    cov = np.linalg.pinv(Aa.T @ Aa)
    dx = -cov @ (Aa.T @ rw)
    return float(dx[-1]), float(math.sqrt(max(cov[-1, -1] * var_factor, 0.0)))


def _bias_share(normal: np.ndarray, cov: np.ndarray, var_factor: float,
                accel_bias_sigma: float) -> tuple[float, np.ndarray]:
    """Share of the horizontal tip variance (weakest direction) owed to the unknown
    accelerometer bias, and that direction (unit north/east vector)."""
    h = cov[3:5, 3:5]
    w, v = np.linalg.eigh(h)
    d = v[:, 1]
    known = normal.copy()
    known[BA, BA] += np.eye(3) * (1e3 / accel_bias_sigma) ** 2   # bias as good as known
    hk = np.linalg.pinv(known)[3:5, 3:5] * var_factor
    full = float(d @ h @ d)
    share = 1.0 - float(d @ hk @ d) / full if full > 0 else 0.0
    return float(np.clip(share, 0.0, 1.0)), d

