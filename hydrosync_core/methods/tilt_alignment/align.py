"""Li et al.'s heading alignment: observation vectors, screening, gradient descent, SVD.

Frames: NED navigation frame, body x forward, y right, z down along the pole; the pole
vector ``l_b = [0, 0, l]`` points from the antenna to the tip. Angles in radians inside.

With the tip fixed, the antenna is ``p(t) = tip − C(t)·l_b``. The IMU gives the attitude
``C'`` with the right roll and pitch but its heading off by a constant ψ:
``C = Rz(ψ)·C'``. Between two GNSS epochs *i*, *j* the antenna moves by
``v_n = p(t_j) − p(t_i)`` (GNSS) and, predicted from the IMU,
``v' = −(C'(t_j) − C'(t_i))·l_b`` (eq. 19), so ``v_n = Rz(ψ)·v'``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from hydrosync_core.errors import HydroSyncError
from hydrosync_core.methods.tilt_alignment.geometry import rz, wrap


class Undetermined(HydroSyncError):
    """The data do not determine the result (discordant vectors, too few vectors)."""


@dataclass
class Vectors:
    """Observation vectors between GNSS epoch pairs (NED, m).

    Attributes
    ----------
    nav : (K, 3) GNSS displacement ``v_n``. imu : (K, 3) IMU-predicted ``v'``.
    pairs : (K, 2) epoch indices (i, j). psi : (K,) per-pair heading (rad, eq. 15-16).
    used : (K,) bool, kept by the screening. short : int, pairs dropped for a horizontal
    length below the minimum.
    """

    nav: np.ndarray
    imu: np.ndarray
    pairs: np.ndarray
    psi: np.ndarray
    used: np.ndarray
    short: int = 0
    centre: float = 0.0
    spread: float = 0.0

    @property
    def n_used(self) -> int:
        return int(self.used.sum())

    @property
    def n_rejected(self) -> int:
        return int(self.used.size - self.used.sum())


def observation_vectors(p_nav: np.ndarray, u_imu: np.ndarray, min_length: float
                        ) -> Vectors:
    """All epoch-pair vectors whose horizontal GNSS length is at least *min_length* (m).

    Parameters
    ----------
    p_nav : (M, 3) antenna positions (NED, m). u_imu : (M, 3) ``C'·l_b`` at the same
    epochs (NED, m).
    """
    i, j = np.triu_indices(len(p_nav), k=1)
    nav = p_nav[j] - p_nav[i]
    imu = -(u_imu[j] - u_imu[i])
    long_enough = np.hypot(nav[:, 0], nav[:, 1]) >= min_length
    nav, imu, pairs = nav[long_enough], imu[long_enough], np.column_stack([i, j])[long_enough]
    return Vectors(nav, imu, pairs, pair_headings(nav, imu), np.ones(len(nav), bool),
                   short=int((~long_enough).sum()))


def pair_headings(nav: np.ndarray, imu: np.ndarray) -> np.ndarray:
    """Per-pair heading ψ_k (rad) from the 2-D coordinate transformation (eqs. 15-16).

    ``x2 = δx + x1·cosψ − y1·sinψ``, ``y2 = δy + x1·sinψ + y1·cosψ`` written for the two
    end points of a pair: the translation cancels in their difference and ψ is the angle
    from the IMU vector to the GNSS vector in the horizontal plane (north x, east y).
    """
    cross = imu[:, 0] * nav[:, 1] - imu[:, 1] * nav[:, 0]
    dot = imu[:, 0] * nav[:, 0] + imu[:, 1] * nav[:, 1]
    return np.arctan2(cross, dot)


def screen(vec: Vectors, k: float, floor: float, max_spread: float, min_vectors: int
           ) -> Vectors:
    """Reject pairs whose ψ_k departs from the bulk; refuse a discordant set.

    A pair is rejected when ``|ψ_k − median| > max(k·1.4826·MAD, floor)`` (rad). The set
    is refused (:class:`Undetermined`) when fewer than *min_vectors* vectors remain,
    fewer than half are kept, or the robust spread ``1.4826·MAD`` exceeds *max_spread*:
    per Li et al., widely different ψ mean too much noise or a faulty IMU.
    """
    if vec.psi.size < min_vectors:
        raise Undetermined(f"only {vec.psi.size} observation vectors long enough "
                           f"(at least {min_vectors} needed): swing the pole wider")
    centre = float(np.angle(np.mean(np.exp(1j * vec.psi))))
    for _ in range(2):  # the circular mean, then the median around it
        centre = centre + float(np.median(wrap(vec.psi - centre)))
    dev = wrap(vec.psi - centre)
    spread = 1.4826 * float(np.median(np.abs(dev)))
    used = np.abs(dev) <= max(k * spread, floor)
    vec.used, vec.centre, vec.spread = used, float(wrap(centre)), spread
    if spread > max_spread:
        raise Undetermined(f"observation vectors disagree: per-pair headings spread "
                           f"{math.degrees(spread):.1f}° (limit {math.degrees(max_spread):g}°)"
                           " — GNSS too noisy or IMU faulty")
    if used.sum() < min_vectors or used.sum() < 0.5 * used.size:
        raise Undetermined(f"only {int(used.sum())} of {used.size} observation vectors agree "
                           f"(at least {min_vectors} and half needed)")
    return vec


def cost(psi, nav: np.ndarray, imu: np.ndarray) -> np.ndarray:
    """J(ψ) = Σ‖v_n − Rz(ψ)·v'‖² / Σ‖v'_h‖² (dimensionless; eqs. 5-8 normalised).

    Normalising by the horizontal IMU vector lengths makes the learning rate independent of
    the swing size: near the minimum the curvature is about 2.
    """
    psi = np.asarray(psi, float)
    c, s = np.cos(psi)[..., None], np.sin(psi)[..., None]
    x, y = imu[:, 0], imu[:, 1]
    rx, ry = c * x - s * y, s * x + c * y
    sq = (nav[:, 0] - rx) ** 2 + (nav[:, 1] - ry) ** 2 + (nav[:, 2] - imu[:, 2]) ** 2
    return sq.sum(axis=-1) / max(float(np.sum(x * x + y * y)), 1e-12)


def _sums(nav: np.ndarray, imu: np.ndarray) -> tuple[float, float, float]:
    D = float(np.sum(imu[:, 0] * nav[:, 0] + imu[:, 1] * nav[:, 1]))
    S = float(np.sum(imu[:, 0] * nav[:, 1] - imu[:, 1] * nav[:, 0]))
    return D, S, max(float(np.sum(imu[:, 0] ** 2 + imu[:, 1] ** 2)), 1e-12)


def gradient(psi: float, nav: np.ndarray, imu: np.ndarray) -> float:
    """dJ/dψ of :func:`cost` (eqs. 9-12): ``2(sinψ·D − cosψ·S)/Σ‖v'_h‖²``."""
    D, S, norm = _sums(nav, imu)
    return 2.0 * (math.sin(psi) * D - math.cos(psi) * S) / norm


@dataclass
class Descent:
    """A gradient-descent solution: ψ (rad), the iterates and whether |L| fell below ε."""

    psi: float
    history: np.ndarray = field(default_factory=lambda: np.zeros(0))
    iterations: int = 0
    converged: bool = False


def descend(nav: np.ndarray, imu: np.ndarray, psi0: float, rate: float, eps: float,
            max_iterations: int) -> Descent:
    """Gradient descent on J(ψ): ``L = α·∇J`` (eq. 13), ``ψ ← ψ − L`` (eq. 14) until |L| < ε.

    Parameters
    ----------
    psi0 : start (rad). rate : learning rate α (rad per unit gradient of the normalised J).
    eps : stop threshold ε on |L| (rad). max_iterations : limit.
    """
    psi, hist = float(psi0), [float(psi0)]
    for it in range(1, max_iterations + 1):
        step = rate * gradient(psi, nav, imu)
        psi -= step
        hist.append(psi)
        if abs(step) < eps:
            return Descent(float(wrap(psi)), np.array(hist), it, True)
    return Descent(float(wrap(psi)), np.array(hist), max_iterations, False)


def closed_form(nav: np.ndarray, imu: np.ndarray) -> float:
    """The exact minimiser of J(ψ): ``atan2(Σ(x'y − y'x), Σ(x'x + y'y))`` (rad)."""
    D, S, _ = _sums(nav, imu)
    return math.atan2(S, D)


def heading_sigma(nav: np.ndarray, imu: np.ndarray, psi: float, n_epochs: int) -> float:
    """Approximate 1σ (rad) of a heading-only fit from its horizontal residuals.

    The pairs share epochs, so the residual scatter is inflated by ``K/(M−1)`` (K pairs,
    M epochs) to count independent information only.
    """
    r = nav[:, :2] - (rz(psi)[:2, :2] @ imu[:, :2].T).T
    h = imu[:, :2]
    perp = (h[:, 0] * r[:, 1] - h[:, 1] * r[:, 0]) / np.maximum(np.hypot(h[:, 0], h[:, 1]),
                                                                  1e-9)
    k = len(nav)
    if k < 2:
        return float("nan")
    s2 = float(np.sum(perp ** 2)) / (k - 1)
    inflation = max(1.0, k / max(n_epochs - 1, 1))
    return math.sqrt(s2 / float(np.sum(h ** 2)) * inflation)


def wahba_svd(nav: np.ndarray, imu: np.ndarray) -> np.ndarray:
    """The rotation R minimising Σ‖v_n − R·v'‖² (Wahba's problem by SVD), 3×3."""
    B = nav.T @ imu
    U, _, Vt = np.linalg.svd(B)
    d = np.sign(np.linalg.det(U) * np.linalg.det(Vt)) or 1.0
    return U @ np.diag([1.0, 1.0, d]) @ Vt


def compensate(p_nav: np.ndarray, C: np.ndarray, length: float) -> np.ndarray:
    """Tilt compensation (eq. 18): tip = antenna + C·l_b, NED (m); C of shape (M, 3, 3)."""
    return p_nav + C[:, :, 2] * length


def horizontal_error_from_heading(psi_err: float, length: float, tilt: float) -> float:
    """Eq. 17: ΔH = ψ·l·sinβ (m) for a heading error ψ (rad), pole *length* (m), tilt β."""
    return psi_err * length * math.sin(tilt)
