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
The weights of the two groups are re-estimated from their residuals (variance
components), and the covariance of the result gives σ of the tip.

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
TH, TIP, BG, BA = slice(0, 3), slice(3, 6), slice(6, 9), slice(9, 12)


@dataclass
class JointResult:
    """Solution of :func:`joint_lsq` (NED, SI units, radians).

    ``bias_share``/``weak_direction``: see the module. ``time_offset_s`` ± ``_std_s``: the
    GNSS time tags' offset against the IMU clock indicated by the residuals (a check: the
    solution assumes the tags as given; :func:`.pipeline.solve_record` applies a significant
    offset to the tags, adjusts again and records it in ``time_offset_applied_s``).
    ``cov`` is the 12×12 covariance (δθ, tip, b_g, b_a); ``sigma_gnss_m`` and
    ``sigma_dv_m_s`` the a-posteriori σ of one GNSS coordinate (horizontal; vertical is
    twice) and of one accelerometer window (m/s); ``rms_gnss_m`` the RMS of the GNSS residuals.
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

    @property
    def weak_sigma_m(self) -> float:
        """1σ (m) of the tip along its weakest horizontal direction."""
        d = self.weak_direction
        if d is None:
            return float("nan")
        return float(np.sqrt(max(d @ self.cov[3:5, 3:5] @ d, 0.0)))

    @property
    def tip_std(self) -> np.ndarray:
        return np.sqrt(np.clip(np.diag(self.cov)[TIP], 0.0, None))

    @property
    def attitude_std(self) -> np.ndarray:
        """1σ (rad) of the initial attitude about north, east and down."""
        return np.sqrt(np.clip(np.diag(self.cov)[TH], 0.0, None))


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


def _model(C, time, accel, gnss_t, length, tip, ba, g, windows):
    """Residuals (GNSS (M,3), accelerometer windows (B,3)) and their Jacobians
    ((M,3,12), (B,3,12))."""
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
    y = np.einsum("kij,kj->ki", C, accel - ba)
    Dy = -skew(y) @ Phi
    Dy[:, :, BA] -= C
    ea = Wq @ (y + g * E_DOWN) + D @ u
    Da = np.einsum("bk,kij->bij", Wq, Dy) + np.einsum("bk,kij->bij", D, Du)
    return u_at, Dg, ea, Da


def joint_lsq(time: np.ndarray, gyro: np.ndarray, accel: np.ndarray, gnss_t: np.ndarray,
              gnss_p: np.ndarray, length: float, C0: np.ndarray, tip0: np.ndarray, *,
              sigma_h: float, sigma_v: float, g: float, block_s: float = 0.25,
              sigma_dv: float = 0.003, gyro_bias_sigma: float = math.radians(0.2),
              accel_bias_sigma: float = 0.05, max_iterations: int = 20, vce_rounds: int = 2,
              cancel_check=None) -> JointResult:
    """Estimate initial attitude, tip and IMU biases from the whole record.

    Parameters
    ----------
    time : (N,) IMU times (s). gyro : (N, 3) rad/s. accel : (N, 3) m/s² (body frame).
    gnss_t : (M,) s. gnss_p : (M, 3) antenna NED (m). length : pole length (m).
    C0 : initial attitude guess (body→NED) at ``time[0]``. tip0 : tip guess (NED, m).
    sigma_h, sigma_v : a-priori GNSS σ (m). g : gravity (m/s²).
    gyro_bias_sigma, accel_bias_sigma : a-priori 1σ of the biases about zero (rad/s,
    m/s², the IMU datasheet's bias stability): a swing in one plane cannot separate the
    accelerometer bias along the swing axis from the tilt out of that plane, so the
    datasheet bounds it.
    block_s : step of the accelerometer windows (s; each twice as long). sigma_dv :
    a-priori σ of one window (m/s). vce_rounds : re-weighting rounds from the residuals.
    """
    C0 = np.array(C0, float)
    tip = np.array(tip0, float)
    bg, ba = np.zeros(3), np.zeros(3)
    windows = _windows(time, block_s)
    s_g, s_a = 1.0, 1.0
    wg = np.array([sigma_h, sigma_h, sigma_v])
    it_total, converged = 0, False
    C = propagate(C0, time, gyro, bg)
    for rnd in range(vce_rounds + 1):
        converged = False
        for _ in range(max_iterations):
            if cancel_check is not None:
                cancel_check()
            it_total += 1
            u_at, Dg, ea, Da = _model(C, time, accel, gnss_t, length, tip, ba, g, windows)
            eg = gnss_p - tip + u_at
            sg = (wg * s_g)[None, :]
            rows = [(Dg / sg[:, :, None]).reshape(-1, NPAR)]
            res = [(eg / sg).ravel()]
            if len(ea):
                rows.append((Da / (sigma_dv * s_a)).reshape(-1, NPAR))
                res.append((ea / (sigma_dv * s_a)).ravel())
            prior = np.zeros((6, NPAR))
            prior[:3, BG] = np.eye(3) / gyro_bias_sigma
            prior[3:, BA] = np.eye(3) / accel_bias_sigma
            rows.append(prior)
            res.append(np.concatenate([bg / gyro_bias_sigma, ba / accel_bias_sigma]))
            A, r = np.vstack(rows), np.concatenate(res)
            dx, *_ = np.linalg.lstsq(A, -r, rcond=None)
            C0 = exp_so3(dx[TH]) @ C0
            tip = tip + dx[TIP]
            bg = bg + dx[BG]
            ba = ba + dx[BA]
            C = propagate(C0, time, gyro, bg)
            if (np.linalg.norm(dx[TH]) < 1e-10 and np.linalg.norm(dx[TIP]) < 1e-8
                    and np.linalg.norm(dx[BG]) < 1e-10):
                converged = True
                break
        u_at, Dg, ea, Da = _model(C, time, accel, gnss_t, length, tip, ba, g, windows)
        eg = gnss_p - tip + u_at
        n_g, n_a = eg.size, ea.size
        red = max(n_g + n_a - NPAR, 1)
        q_g = float(np.sum((eg / (wg * s_g)) ** 2))
        q_a = float(np.sum((ea / (sigma_dv * s_a)) ** 2)) if n_a else 0.0
        if rnd < vce_rounds:  # variance components, redundancy shared by group size
            s_g *= math.sqrt(q_g / max(red * n_g / (n_g + n_a), 1.0))
            if n_a:
                s_a *= math.sqrt(q_a / max(red * n_a / (n_g + n_a), 1.0))
            s_g, s_a = float(np.clip(s_g, 0.05, 50.0)), float(np.clip(s_a, 0.01, 1e3))
    sg = (wg * s_g)[None, :]
    rows = [(Dg / sg[:, :, None]).reshape(-1, NPAR)]
    if len(ea):
        rows.append((Da / (sigma_dv * s_a)).reshape(-1, NPAR))
    prior = np.zeros((6, NPAR))
    prior[:3, BG] = np.eye(3) / gyro_bias_sigma
    prior[3:, BA] = np.eye(3) / accel_bias_sigma
    A = np.vstack(rows + [prior])
    var_factor = max((q_g + q_a) / red, 1.0)
    normal = A.T @ A
    cov = np.linalg.pinv(normal) * var_factor
    share, weak = _bias_share(normal, cov, var_factor, accel_bias_sigma)
    # second-order check of the GNSS↔IMU time alignment: one Gauss-Newton step of the
    # solution augmented by a time offset τ (GNSS tag t_j is the pole at t_j + τ:
    # ∂e_j/∂τ = du/dt(t_j)), from the converged solution; the solution itself is kept
    r_all = [(eg / sg).ravel()]
    if len(ea):
        r_all.append((ea / (sigma_dv * s_a)).ravel())
    r_all.append(np.concatenate([bg / gyro_bias_sigma, ba / accel_bias_sigma]))
    tau, tau_std = _time_offset(A, np.concatenate(r_all), C, time, gnss_t, length, sg,
                                var_factor)
    return JointResult(C0, tip, bg, ba, cov, C, it_total, converged, sigma_h * s_g,
                       sigma_dv * s_a, float(np.sqrt(np.mean(eg ** 2))), eg,
                       int(windows[0].shape[0]), share, weak, tau, tau_std)


def _time_offset(A: np.ndarray, r: np.ndarray, C: np.ndarray, time: np.ndarray,
                 gnss_t: np.ndarray, length: float, sg: np.ndarray, var_factor: float
                 ) -> tuple[float, float]:
    """Time offset τ (s) of the GNSS tags against the IMU and its 1σ, from the weighted
    design *A*, residuals *r* (GNSS rows first) of the converged solution."""
    u = C[:, :, 2] * length
    n = time.size
    k = np.clip(np.searchsorted(time, gnss_t, side="right") - 1, 0, n - 2)
    rate = (u[k + 1] - u[k]) / (time[k + 1] - time[k])[:, None]
    col = np.zeros(A.shape[0])
    col[:rate.size] = (rate / sg).ravel()
    Aa = np.column_stack([A, col])
    cov = np.linalg.pinv(Aa.T @ Aa)
    dx = -cov @ (Aa.T @ r)
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

