"""Total-least-squares plane fit (seed eqs. [0051]-[0088]).

The plane ``a x + b y + c z = d`` with ``a² + b² + c² = 1`` that minimises the sum of
squared point-to-plane distances has its normal ``(a, b, c)`` along the eigenvector of
the smallest eigenvalue of the centred scatter matrix A ([0080], ``A x = λ x``); that
eigenvalue is the sum of squared distances ([0087]) and ``d = n · centroid`` ([0067]).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class PlaneFit:
    """A fitted plane in the frame of its points (target ENU, m).

    Attributes
    ----------
    normal : (3,) unit normal; d : offset (m) with ``normal · x = d``; centroid : (3,) m;
    rms : RMS point-to-plane distance (m); n : number of points;
    flatness : smallest / middle eigenvalue (near 0 for a good plane, ~1 for a line/blob).
    """

    normal: np.ndarray
    d: float
    centroid: np.ndarray
    rms: float
    n: int
    flatness: float
    axes: np.ndarray | None = None
    eigvals: np.ndarray | None = None
    cov: np.ndarray | None = None

    def covariance(self) -> np.ndarray:
        """Covariance (3, 3) of (tilt about in-plane axis 1, tilt about axis 2 [rad], offset
        along the normal at the centroid [m]): ``σ²/λ_i`` and ``σ²/n`` with σ the RMS
        (or the explicit ``cov`` given for a design-derived plane)."""
        if self.cov is not None:
            return self.cov
        if self.eigvals is None or self.n < 4:
            return np.zeros((3, 3))
        var = self.rms**2 * self.n / (self.n - 3)
        lam = np.maximum(self.eigvals[1:], 1e-12)
        return np.diag([var / lam[0], var / lam[1], var / self.n])

    def distance(self, points: np.ndarray) -> np.ndarray:
        """Signed distances (m) of *points* (N, 3) to the plane."""
        return points @ self.normal - self.d

    def shifted(self, offset: float) -> PlaneFit:
        """The parallel plane moved by *offset* m along the normal."""
        return PlaneFit(self.normal, self.d + offset, self.centroid + offset * self.normal,
                        self.rms, self.n, self.flatness, self.axes, self.eigvals, self.cov)


def fit_plane(points: np.ndarray, orient: np.ndarray | None = None) -> PlaneFit:
    """Fit a plane to *points* (N >= 3, 3); flip the normal to agree with *orient*."""
    points = np.asarray(points, dtype=float)
    if len(points) < 3:
        raise ValueError(f"a plane needs at least 3 points, got {len(points)}")
    centroid = points.mean(axis=0)
    # Centred scatter matrix A ([0080]); eigh returns eigenvalues in ascending order.
    delta = points - centroid
    scatter = delta.T @ delta
    values, vectors = np.linalg.eigh(scatter)
    normal = vectors[:, 0]
    if orient is not None and normal @ orient < 0:
        normal = -normal
    # λ_min = Σ d_i² ([0087]) -> RMS distance.
    rms = float(np.sqrt(max(values[0], 0.0) / len(points)))
    flatness = float(values[0] / values[1]) if values[1] > 0 else 1.0
    axes = vectors.copy()
    axes[:, 0] = normal
    return PlaneFit(normal, float(normal @ centroid), centroid, rms, len(points), flatness,
                    axes, values)


def angle_deg(n1: np.ndarray, n2: np.ndarray) -> float:
    """Unsigned angle between two unit normals, degrees (seed [0089]-[0093])."""
    return float(np.degrees(np.arccos(np.clip(abs(n1 @ n2), -1.0, 1.0))))
