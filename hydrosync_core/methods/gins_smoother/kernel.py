"""Compiled core of the GNSS/INS smoother: strapdown mechanisation, error-state EKF, RTS.

Everything here runs under :func:`numba.njit` (compiled on first use and cached on disk);
the functions take and return plain float64 arrays so that :mod:`.filter` can wrap them.

Frames and conventions
----------------------
* Body frame b: x forward, y right, z down (FRD). Navigation frame n: local level NED.
* Position: geodetic latitude and longitude in **radians**, ellipsoidal height in metres
  (WGS-84). Velocity: NED, m/s. Attitude: unit quaternion ``q = [w, x, y, z]`` of
  ``C_b^n = Rz(yaw)·Ry(pitch)·Rx(roll)``.
* IMU errors: gyro bias ``bg`` (rad/s), accelerometer bias ``ba`` (m/s²), scale factors
  ``sg``, ``sa`` (dimensionless); the compensated increments are
  ``Δθ = (Δθ̃ − bg·Δt) / (1 + sg)`` and ``Δv = (Δṽ − ba·Δt) / (1 + sa)``.

The total state vector (25 values) is ``[lat, lon, h, vN, vE, vD, qw, qx, qy, qz, bg(3),
ba(3), sg(3), sa(3), bG(3)]``; ``bG`` is the time-correlated GNSS position error (NED, m;
the fix is the antenna position plus ``bG`` plus white noise).

Error state (15 or 21 states, Wang et al. eq. 1, extended by scale factors, plus 3 with
the Gauss–Markov GNSS error: 18 or 24): ``δr`` (NED, m), ``δv`` (NED, m/s), ``φ`` (rad),
``δbg``, ``δba``, [``δsg``, ``δsa``], [``δbG``].
Position and velocity errors are *computed minus true*; the attitude error φ is defined by
``C_true = exp(φ×)·C_computed``; the IMU-error states are *true minus estimated*. The
closed-loop feedback is therefore ``r −= δr``, ``v −= δv``, ``q ← exp(φ)⊗q``, ``b += δb``
(the convention of the KF-GINS software, so its YAML noise figures mean the same here).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

WIE = 7.2921151467e-5  # earth rotation rate, rad/s
A_WGS = 6378137.0
E2_WGS = 0.00669437999013
NX = 25  # total-state length
GNSS_X = 22  # total-state index of the GNSS error estimate bG


@njit(cache=True)
def n_imu(ns):
    """Error states up to and including the IMU errors (15 or 21) of an ns-state filter;
    the remaining ``ns − n_imu`` (0 or 3) are the GNSS error."""
    return 21 if ns >= 21 else 15


@njit(cache=True)
def tix(i, ns):
    """Total-state index of error state *i* ≥ 9 (IMU errors, then the GNSS error)."""
    ni = n_imu(ns)
    return i + 1 if i < ni else GNSS_X + i - ni


@njit(cache=True)
def radii(lat):
    """Meridian and prime-vertical radii of curvature (m) at geodetic latitude (rad)."""
    s = math.sin(lat)
    w = 1.0 - E2_WGS * s * s
    rn = A_WGS / math.sqrt(w)
    rm = A_WGS * (1.0 - E2_WGS) / (w * math.sqrt(w))
    return rm, rn


@njit(cache=True)
def gravity(lat, h):
    """Normal gravity (m/s², positive down) at latitude (rad) and height (m)."""
    s2 = math.sin(lat) ** 2
    return (9.7803267715 * (1.0 + 0.0052790414 * s2 + 0.0000232718 * s2 * s2)
            + h * (0.0000000043977311 * s2 - 0.0000030876910891) + 0.0000000000007211 * h * h)


@njit(cache=True)
def skew(v):
    m = np.zeros((3, 3))
    m[0, 1] = -v[2]
    m[0, 2] = v[1]
    m[1, 0] = v[2]
    m[1, 2] = -v[0]
    m[2, 0] = -v[1]
    m[2, 1] = v[0]
    return m


@njit(cache=True)
def cross(a, b):
    out = np.empty(3)
    out[0] = a[1] * b[2] - a[2] * b[1]
    out[1] = a[2] * b[0] - a[0] * b[2]
    out[2] = a[0] * b[1] - a[1] * b[0]
    return out


@njit(cache=True)
def qmul(p, q):
    out = np.empty(4)
    out[0] = p[0] * q[0] - p[1] * q[1] - p[2] * q[2] - p[3] * q[3]
    out[1] = p[0] * q[1] + p[1] * q[0] + p[2] * q[3] - p[3] * q[2]
    out[2] = p[0] * q[2] - p[1] * q[3] + p[2] * q[0] + p[3] * q[1]
    out[3] = p[0] * q[3] + p[1] * q[2] - p[2] * q[1] + p[3] * q[0]
    return out


@njit(cache=True)
def qrotvec(v):
    """Quaternion of the rotation vector *v* (rad)."""
    a = math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
    out = np.empty(4)
    out[0] = math.cos(0.5 * a)
    k = 0.5 - a * a / 48.0 if a < 1e-8 else math.sin(0.5 * a) / a
    out[1] = k * v[0]
    out[2] = k * v[1]
    out[3] = k * v[2]
    return out


@njit(cache=True)
def qlog(q):
    """Rotation vector (rad) of the unit quaternion *q*."""
    w = q[0]
    if w < 0.0:
        q = -q
        w = -w
    s = math.sqrt(q[1] * q[1] + q[2] * q[2] + q[3] * q[3])
    out = np.empty(3)
    k = 2.0 if s < 1e-12 else 2.0 * math.atan2(s, w) / s
    out[0] = k * q[1]
    out[1] = k * q[2]
    out[2] = k * q[3]
    return out


@njit(cache=True)
def qconj(q):
    return np.array([q[0], -q[1], -q[2], -q[3]])


@njit(cache=True)
def qdcm(q):
    """``C_b^n`` of the quaternion ``q = [w, x, y, z]``."""
    w, x, y, z = q[0], q[1], q[2], q[3]
    c = np.empty((3, 3))
    c[0, 0] = w * w + x * x - y * y - z * z
    c[0, 1] = 2 * (x * y - w * z)
    c[0, 2] = 2 * (x * z + w * y)
    c[1, 0] = 2 * (x * y + w * z)
    c[1, 1] = w * w - x * x + y * y - z * z
    c[1, 2] = 2 * (y * z - w * x)
    c[2, 0] = 2 * (x * z - w * y)
    c[2, 1] = 2 * (y * z + w * x)
    c[2, 2] = w * w - x * x - y * y + z * z
    return c


@njit(cache=True)
def rates(lat, h, v):
    """Earth rate and transport rate in n (rad/s) and the radii at (lat, h, v)."""
    rm, rn = radii(lat)
    wie = np.array([WIE * math.cos(lat), 0.0, -WIE * math.sin(lat)])
    wen = np.array([v[1] / (rn + h), -v[0] / (rm + h), -v[1] * math.tan(lat) / (rn + h)])
    return wie, wen, rm, rn


@njit(cache=True)
def mechanise(x, dth, dv, dth_p, dv_p, dt):
    """One strapdown step in place on the total state *x* (module docstring).

    *dth*, *dv* are this interval's compensated angle (rad) and velocity (m/s) increments,
    *dth_p*, *dv_p* the previous interval's (for the coning and sculling terms); *dt* in s.
    Velocity with rotation and sculling compensation and the n-frame rotation over the
    step, position with the mid-interval velocity, attitude with the coning correction and
    the rotation of the n frame (earth rate plus transport rate at mid-interval).
    """
    lat, lon, h = x[0], x[1], x[2]
    v = x[3:6].copy()
    q = x[6:10].copy()
    c = qdcm(q)
    # velocity: specific-force increment with rotation + sculling compensation
    dvfb = dv + 0.5 * cross(dth, dv) + (cross(dth_p, dv) + cross(dv_p, dth)) / 12.0
    wie, wen, rm, rn = rates(lat, h, v)
    g = gravity(lat, h)
    dvgn = (np.array([0.0, 0.0, g]) - cross(2.0 * wie + wen, v)) * dt
    zeta = (wie + wen) * dt
    dvfn = (np.eye(3) - 0.5 * skew(zeta)) @ (c @ dvfb)
    vmid = v + 0.5 * (dvfn + dvgn)
    # extrapolate to mid-interval and recompute
    latm = lat + 0.5 * dt * vmid[0] / (rm + h)
    hm = h - 0.5 * dt * vmid[2]
    wie, wen, rm, rn = rates(latm, hm, vmid)
    g = gravity(latm, hm)
    dvgn = (np.array([0.0, 0.0, g]) - cross(2.0 * wie + wen, vmid)) * dt
    zeta = (wie + wen) * dt
    dvfn = (np.eye(3) - 0.5 * skew(zeta)) @ (c @ dvfb)
    vnew = v + dvfn + dvgn
    # position with the mid-interval velocity
    vm = 0.5 * (v + vnew)
    hnew = h - vm[2] * dt
    hmid = 0.5 * (h + hnew)
    rm, rn = radii(lat)
    latnew = lat + vm[0] * dt / (rm + hmid)
    latmid = 0.5 * (lat + latnew)
    rm, rn = radii(latmid)
    lonnew = lon + vm[1] * dt / ((rn + hmid) * math.cos(latmid))
    # attitude: body rotation with coning, n-frame rotation at mid-interval
    rot = dth + cross(dth_p, dth) / 12.0
    wie, wen, rm, rn = rates(latmid, hmid, vm)
    qnn = qrotvec(-(wie + wen) * dt)
    qn = qmul(qmul(qnn, q), qrotvec(rot))
    qn /= math.sqrt(qn[0] ** 2 + qn[1] ** 2 + qn[2] ** 2 + qn[3] ** 2)
    x[0], x[1], x[2] = latnew, lonnew, hnew
    x[3:6] = vnew
    x[6:10] = qn


@njit(cache=True)
def system_matrix(x, fb, wb, ns, tcorr, tcorr_g):
    """Continuous error-state matrix F (ns × ns) at total state *x*.

    *fb* (m/s²) and *wb* (rad/s): compensated specific force and angular rate in b.
    *tcorr*: correlation time (s) of the first-order Gauss-Markov IMU errors; *tcorr_g*
    that of the GNSS error states (when ns is 18 or 24).
    """
    lat, h = x[0], x[2]
    v = x[3:6]
    c = qdcm(x[6:10])
    rm, rn = radii(lat)
    rmh, rnh = rm + h, rn + h
    g = gravity(lat, h)
    sl, cl, tl = math.sin(lat), math.cos(lat), math.tan(lat)
    wie = np.array([WIE * cl, 0.0, -WIE * sl])
    wen = np.array([v[1] / rnh, -v[0] / rmh, -v[1] * tl / rnh])
    F = np.zeros((ns, ns))
    # position
    F[0, 0] = -v[2] / rmh
    F[0, 2] = v[0] / rmh
    F[1, 0] = v[1] * tl / rnh
    F[1, 1] = -(v[2] + v[0] * tl) / rnh
    F[1, 2] = v[1] / rnh
    for i in range(3):
        F[i, 3 + i] = 1.0
    # velocity
    F[3, 0] = -2 * v[1] * WIE * cl / rmh - v[1] ** 2 / rmh / rnh / cl ** 2
    F[3, 2] = v[0] * v[2] / rmh / rmh - v[1] ** 2 * tl / rnh / rnh
    F[4, 0] = (2 * WIE * (v[0] * cl - v[2] * sl) / rmh + v[0] * v[1] / rmh / rnh / cl ** 2)
    F[4, 2] = (v[1] * v[2] + v[0] * v[1] * tl) / rnh / rnh
    F[5, 0] = 2 * WIE * v[1] * sl / rmh
    F[5, 2] = -v[1] ** 2 / rnh / rnh - v[0] ** 2 / rmh / rmh + 2 * g / (math.sqrt(rm * rn) + h)
    F[3, 3] = v[2] / rmh
    F[3, 4] = -2 * (WIE * sl + v[1] * tl / rnh)
    F[3, 5] = v[0] / rmh
    F[4, 3] = 2 * WIE * sl + v[1] * tl / rnh
    F[4, 4] = (v[2] + v[0] * tl) / rnh
    F[4, 5] = 2 * WIE * cl + v[1] / rnh
    F[5, 3] = -2 * v[0] / rmh
    F[5, 4] = -2 * (WIE * cl + v[1] / rnh)
    fn = c @ fb
    F[3:6, 6:9] = skew(fn)
    F[3:6, 12:15] = c
    # attitude
    F[6, 0] = -WIE * sl / rmh
    F[6, 2] = v[1] / rnh / rnh
    F[7, 2] = -v[0] / rmh / rmh
    F[8, 0] = -WIE * cl / rmh - v[1] / rmh / rnh / cl ** 2
    F[8, 2] = -v[1] * tl / rnh / rnh
    F[6, 4] = 1.0 / rnh
    F[7, 3] = -1.0 / rmh
    F[8, 4] = -tl / rnh
    F[6:9, 6:9] = -skew(wie + wen)
    F[6:9, 9:12] = -c
    ni = n_imu(ns)
    for i in range(9, ni):
        F[i, i] = -1.0 / tcorr
    for i in range(ni, ns):
        F[i, i] = -1.0 / tcorr_g
    if ni == 21:
        for i in range(3):
            for j in range(3):
                F[3 + i, 18 + j] = c[i, j] * fb[j]
                F[6 + i, 15 + j] = -c[i, j] * wb[j]
    return F


@njit(cache=True)
def noise_gain(x, ns):
    """Noise input matrix G (ns × ns): white noise of ARW, VRW and the GM drivers."""
    c = qdcm(x[6:10])
    G = np.zeros((ns, ns))
    G[3:6, 3:6] = c
    G[6:9, 6:9] = c
    for i in range(9, ns):
        G[i, i] = 1.0
    return G


@njit(cache=True)
def feedback(x, dx, ns):
    """Apply the error-state estimate *dx* to the total state *x* in place (closed loop)."""
    lat, h = x[0], x[2]
    rm, rn = radii(lat)
    x[0] -= dx[0] / (rm + h)
    x[1] -= dx[1] / ((rn + h) * math.cos(lat))
    x[2] += dx[2]
    x[3] -= dx[3]
    x[4] -= dx[4]
    x[5] -= dx[5]
    qn = qmul(qrotvec(dx[6:9]), x[6:10])
    x[6:10] = qn / math.sqrt(np.sum(qn * qn))
    for i in range(9, ns):
        x[tix(i, ns)] += dx[i]


@njit(cache=True)
def difference(a, b, ns):
    """Error state of *a* taken as the computed state and *b* as the truth.

    ``feedback(a, difference(a, b))`` gives *b* to first order (exactly in attitude).
    """
    d = np.zeros(ns)
    rm, rn = radii(a[0])
    d[0] = (a[0] - b[0]) * (rm + a[2])
    d[1] = (a[1] - b[1]) * (rn + a[2]) * math.cos(a[0])
    d[2] = -(a[2] - b[2])
    d[3:6] = a[3:6] - b[3:6]
    d[6:9] = qlog(qmul(b[6:10], qconj(a[6:10])))
    for i in range(9, ns):
        d[i] = b[tix(i, ns)] - a[tix(i, ns)]
    return d


@njit(cache=True)
def _update(x, P, H, z, R, ns, gate):
    """Kalman update with Joseph form and closed-loop feedback; False if gated out."""
    S = H @ P @ H.T + R
    Si = np.linalg.inv(S)
    if gate > 0.0:
        nis = z @ Si @ z
        if nis > gate:
            return False
    K = P @ H.T @ Si
    dx = K @ z
    IKH = np.eye(ns) - K @ H
    P[:, :] = IKH @ P @ IKH.T + K @ R @ K.T
    P[:, :] = 0.5 * (P + P.T)
    feedback(x, dx, ns)
    return True


@njit(cache=True)
def compensate(x, dth_raw, dv_raw, dt, ns):
    """Bias and scale-factor compensated increments (rad, m/s)."""
    dth = dth_raw - x[10:13] * dt
    dv = dv_raw - x[13:16] * dt
    if ns >= 21:
        dth = dth / (1.0 + x[16:19])
        dv = dv / (1.0 + x[19:22])
    return dth, dv


@njit(cache=True)
def start_run(t, inc, i0, x, P, state, ns, nominal_dt, tg, traj, node_idx, xp_n, xf_n, Pp_n,
              Pf_n, Phi_n):
    """First call of :func:`forward`: the GNSS pointer past ``t[i0]``, the previous
    compensated increments (coning and sculling need them) and node 0 at ``t[i0]``."""
    ng = tg.shape[0]
    g = 0
    while g < ng and tg[g] <= t[i0]:
        g += 1
    state[4] = g
    if i0 > 0:
        dtp = t[i0] - t[i0 - 1]
        if dtp <= 0.0 or dtp > 0.1:
            dtp = nominal_dt
        dth_p, dv_p = compensate(x, inc[i0, 0:3], inc[i0, 3:6], dtp, ns)
        state[6:9] = dth_p
        state[9:12] = dv_p
    node_idx[0] = i0
    xp_n[0] = x
    xf_n[0] = x
    Pp_n[0] = P
    Pf_n[0] = P
    Phi_n[0] = np.eye(ns)
    traj[0] = x[0:10]
    state[2] = t[i0]
    state[3] = t[i0]
    state[5] = 1


@njit(cache=True)
def propagate_covariance(x, P, Phi, fb, wb, tsum, ns, qc, tcorr, tcorr_g):
    """Covariance over a block of *tsum* seconds with the block's mean specific force *fb*
    and angular rate *wb*: second-order transition, trapezoidal process noise; *Phi*
    accumulates the transition since the last node (all in place)."""
    F = system_matrix(x, fb, wb, ns, tcorr, tcorr_g) * tsum
    Phb = np.eye(ns) + F + 0.5 * (F @ F)
    G = noise_gain(x, ns)
    GQG = (G * qc) @ G.T
    Q = 0.5 * (Phb @ GQG @ Phb.T + GQG) * tsum
    P[:, :] = Phb @ P @ Phb.T + Q
    Phi[:, :] = Phb @ Phi


@njit(cache=True)
def gnss_update(x, P, ns, t_j, tg_g, llh_g_g, std_g_g, lever, gate, innov_g, innov_cov_g):
    """GNSS position update at IMU epoch time *t_j* with the fix of time *tg_g*: lever
    arm, time alignment by the velocity, the GNSS error state when present. Writes the
    innovation and its predicted covariance; True if applied (not gated out)."""
    c = qdcm(x[6:10])
    la = c @ lever
    rm, rn = radii(x[0])
    dtg = tg_g - t_j
    zn = (x[0] - llh_g_g[0]) * (rm + x[2]) + la[0] + x[3] * dtg
    ze = (x[1] - llh_g_g[1]) * (rn + x[2]) * math.cos(x[0]) + la[1] + x[4] * dtg
    zd = -(x[2] - llh_g_g[2]) + la[2] + x[5] * dtg
    z = np.array([zn, ze, zd])
    H = np.zeros((3, ns))
    H[0, 0] = 1.0
    H[1, 1] = 1.0
    H[2, 2] = 1.0
    H[:, 6:9] = skew(la)
    ni = n_imu(ns)
    if ns > ni:  # fix − estimated GNSS error; error state true − estimated
        for c3 in range(3):
            z[c3] += x[GNSS_X + c3]
            H[c3, ni + c3] = -1.0
    R = np.diag(std_g_g ** 2)
    innov_g[:] = z
    innov_cov_g[:, :] = H @ P @ H.T + R
    return _update(x, P, H, z, R, ns, gate)


@njit(cache=True)
def constraint_update(x, P, ns, is_static, zupt_speed, zupt_std, nhc, nhc_std, c_vb):
    """Zero-velocity update when the IMU is quiet and the filter slow, else the
    non-holonomic constraint (lateral and vertical vehicle-frame velocity zero) if on."""
    c = qdcm(x[6:10])
    speed = math.sqrt(np.sum(x[3:6] ** 2))
    if is_static and speed < zupt_speed:
        H = np.zeros((3, ns))
        H[0, 3] = 1.0
        H[1, 4] = 1.0
        H[2, 5] = 1.0
        _update(x, P, H, x[3:6].copy(), np.eye(3) * zupt_std ** 2, ns, 0.0)
    elif nhc:
        cvn = c_vb @ c.T
        vv = cvn @ x[3:6]
        H = np.zeros((2, ns))
        H[:, 3:6] = cvn[1:3, :]
        H[:, 6:9] = -(cvn @ skew(x[3:6]))[1:3, :]
        R = np.eye(2) * nhc_std ** 2
        _update(x, P, H, vv[1:3].copy(), R, ns, 0.0)


@njit(cache=True)
def forward(t, inc, i0, ja, jb, x, P, Phi, state, qc, ns, tcorr, tcorr_g, nominal_dt, prop_n,
            tg, llh_g, std_g, lever, gate,
            nhc, nhc_std, c_vb, con_interval, static, zupt_std, zupt_speed,
            max_node_dt,
            traj, node_idx, xp_n, xf_n, Pp_n, Pf_n, Phi_n, innov, innov_cov, gnss_used):
    """Forward closed-loop EKF over IMU epochs ``ja … jb`` (inclusive) of a run from ``i0``.

    Called repeatedly on consecutive chunks; *x*, *P*, *Phi* and *state* carry the filter
    between calls and are updated in place (``state[5]`` = number of nodes written).

    The named steps are their own compiled functions (:func:`start_run`,
    :func:`propagate_covariance`, :func:`gnss_update`, :func:`constraint_update`); the
    epoch loop and its carry stay here, because numba cannot return the dozen scalars the
    loop carries from a helper without packing them into arrays on every epoch.

    Parameters
    ----------
    t : (n,) float64
        IMU epoch times (end of each interval), s.
    inc : (n, 6) float64
        Raw angle (rad) and velocity (m/s) increments, body FRD.
    x, P
        Total state at ``t[i0]`` and its error covariance (ns × ns) on the first call.
    Phi : (ns, ns)
        Transition accumulated since the last node (identity on the first call).
    state : (18,)
        Carry: block time and count, last node and constraint times, GNSS pointer, node
        count, previous compensated increments, block sums (zeros on the first call).
    qc : (ns,) float64
        Continuous white-noise densities: VRW² (m²/s³), ARW² (rad²/s), then
        ``2σ²/T`` of the Gauss-Markov IMU errors and GNSS errors.
    tcorr, tcorr_g : float
        Correlation times (s) of the IMU errors and of the GNSS error states.
    tg, llh_g, std_g
        GNSS epoch times (s), antenna lat/lon (rad)/h (m), N/E/D std (m) of the white
        part of the GNSS error (the time-correlated part is the GNSS error state).
    lever : (3,)
        Antenna lever arm in b (m).
    gate : float
        Innovation gate on the normalised innovation squared (0 = off).
    nhc, nhc_std, c_vb
        Non-holonomic constraint on/off, std of the lateral/vertical vehicle velocity
        (m/s), rotation vehicle ← body of the mounting angles.
    con_interval : float
        Interval (s) between motion-constraint updates.
    static : (n,) bool
        IMU epochs detected as quiet (ZUPT candidates); *zupt_speed* (m/s) is the
        largest INS speed at which a ZUPT is applied, *zupt_std* its std (m/s).
    max_node_dt : float
        Longest interval (s) between stored smoother nodes.
    traj : (i1-i0+1, 10)
        Output: navigation state after updates at each epoch.
    node_idx, xp_n, xf_n, Pp_n, Pf_n, Phi_n
        Output, per smoother node: IMU index, predicted and filtered total states and
        covariances, transition matrix from the previous node.
    innov, innov_cov, gnss_used
        Output per GNSS epoch: innovation (NED m, computed − measured, the GNSS error
        estimate removed), its predicted covariance ``S = HPHᵀ + R`` (3 × 3) and 1 if
        applied.
    """
    ng = tg.shape[0]
    if state[5] == 0:
        start_run(t, inc, i0, x, P, state, ns, nominal_dt, tg, traj, node_idx, xp_n, xf_n,
                  Pp_n, Pf_n, Phi_n)
    tsum = state[0]
    nblk = int(state[1])
    last_node_t = state[2]
    last_con_t = state[3]
    g = int(state[4])
    k = int(state[5])
    dth_p = state[6:9].copy()
    dv_p = state[9:12].copy()
    fsum = state[12:15].copy()
    wsum = state[15:18].copy()
    i1 = i0 + traj.shape[0] - 1
    for j in range(max(ja, i0 + 1), jb + 1):
        dt = t[j] - t[j - 1]
        if dt <= 0.0 or dt > 0.1:
            dt = nominal_dt
        dth, dv = compensate(x, inc[j, 0:3], inc[j, 3:6], dt, ns)
        mechanise(x, dth, dv, dth_p, dv_p, dt)
        dth_p = dth
        dv_p = dv
        fsum += dv
        wsum += dth
        tsum += dt
        nblk += 1
        # is this epoch a node?
        has_gnss = g < ng and tg[g] <= t[j]
        con_due = (t[j] - last_con_t >= con_interval - 1e-9) and (
            nhc or (static[j] and math.sqrt(np.sum(x[3:6] ** 2)) < zupt_speed))
        is_node = has_gnss or con_due or (t[j] - last_node_t >= max_node_dt - 1e-9) or j == i1
        if nblk >= prop_n or is_node:
            propagate_covariance(x, P, Phi, fsum / tsum, wsum / tsum, tsum, ns, qc, tcorr,
                                 tcorr_g)
            fsum[:] = 0.0
            wsum[:] = 0.0
            tsum = 0.0
            nblk = 0
        if is_node:
            node_idx[k] = j
            xp_n[k] = x
            Pp_n[k] = P
            Phi_n[k] = Phi
            while g < ng and tg[g] <= t[j]:
                if gnss_update(x, P, ns, t[j], tg[g], llh_g[g], std_g[g], lever, gate,
                               innov[g], innov_cov[g]):
                    gnss_used[g] = 1
                g += 1
            if con_due:
                last_con_t = t[j]
                constraint_update(x, P, ns, static[j], zupt_speed, zupt_std, nhc, nhc_std,
                                  c_vb)
            xf_n[k] = x
            Pf_n[k] = P
            Phi[:, :] = np.eye(ns)
            last_node_t = t[j]
            k += 1
        traj[j - i0] = x[0:10]
    state[0] = tsum
    state[1] = nblk
    state[2] = last_node_t
    state[3] = last_con_t
    state[4] = g
    state[5] = k
    state[6:9] = dth_p
    state[9:12] = dv_p
    state[12:15] = fsum
    state[15:18] = wsum


@njit(cache=True)
def smooth(xp_n, xf_n, Pp_n, Pf_n, Phi_n, nn, ns, xs_n, es_n, ep_n, Ps_diag):
    """Rauch-Tung-Striebel backward pass over the *nn* stored nodes, on the total state.

    ``x_k|N = x_k|k ⊕ A_k·(x_k+1|N ⊖ x_k+1|k)`` with ``A_k = P_k|k Φᵀ P_k+1|k⁻¹`` and
    ``P_k|N = P_k|k + A_k (P_k+1|N − P_k+1|k) A_kᵀ``, where ⊖ is :func:`difference` and ⊕
    :func:`feedback` (attitude by rotation composition).

    Outputs: ``xs_n`` smoothed total states, ``es_n[k]`` the smoothed error of the filtered
    state ``x_k|k`` and ``ep_n[k]`` that of the predicted state ``x_k|k-1`` (both in the
    error-state convention), ``Ps_diag`` the diagonal of ``P_k|N``.
    """
    k = nn - 1
    xs_n[k] = xf_n[k]
    Ps = Pf_n[k].copy()
    Ps_diag[k] = np.diag(Ps)
    es_n[k] = 0.0
    ep_n[k] = difference(xp_n[k], xf_n[k], ns)
    for k in range(nn - 2, -1, -1):
        Pp = Pp_n[k + 1]
        s = np.sqrt(np.diag(Pp))
        Ppn = Pp / np.outer(s, s)
        M = (Phi_n[k + 1] @ Pf_n[k]) / s.reshape(-1, 1)
        At = np.linalg.solve(Ppn, M) / s.reshape(-1, 1)  # Aᵀ = Pp⁻¹ Φ Pf
        A = At.T
        e1 = difference(xp_n[k + 1], xs_n[k + 1], ns)
        ep_n[k + 1] = e1
        ek = A @ e1
        es_n[k] = ek
        xk = xf_n[k].copy()
        feedback(xk, ek, ns)
        xs_n[k] = xk
        Ps = Pf_n[k] + A @ (Ps - Pp) @ At
        Ps = 0.5 * (Ps + Ps.T)
        Ps_diag[k] = np.diag(Ps)
    ep_n[0] = es_n[0]
    return 0


@njit(cache=True)
def apply_corrections(traj, rel_idx, es_n, ep_n, t, nn, ns, out):
    """Smoothed trajectory at IMU rate: the forward trajectory *traj* corrected by the
    smoothed error interpolated linearly in time between nodes.

    Between node k (filtered, error ``es_n[k]``) and node k+1 (predicted, error
    ``ep_n[k+1]``) the forward trajectory is pure propagation, so the error is
    interpolated between those two; at a node itself ``es_n`` is used.
    """
    x = np.zeros(NX)
    for k in range(nn - 1):
        a = rel_idx[k]
        b = rel_idx[k + 1]
        ta = t[a]
        tb = t[b]
        for j in range(a, b):
            w = 0.0 if j == a else (t[j] - ta) / (tb - ta)
            e = (1.0 - w) * es_n[k] + w * ep_n[k + 1]
            x[0:10] = traj[j]
            feedback(x, e, 9)
            out[j] = x[0:10]
    b = rel_idx[nn - 1]
    x[0:10] = traj[b]
    feedback(x, es_n[nn - 1], 9)
    out[b] = x[0:10]
