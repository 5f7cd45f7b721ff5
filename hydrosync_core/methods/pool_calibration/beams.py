"""Where a multibeam beam meets a plane: the point a range error does not move.

A sounding lies on its beam at the measured range; a range error moves it along the beam,
so both across its face and off the face's plane. Anything computed from the sounding's own
position that the fit also differentiates (the lever of a rotation, the cut at a face's
edge) then correlates with the residual, and the least-squares solution is biased by a term
in σ_range² (errors in the variables): the fit turns the beams towards grazing the faces,
where their noise is smallest. On a block target the yaw and lever x this leaves are
weakly determined, and the bias reached -4σ (#24, simulated passes without any build
error). Evaluated where the beam meets the plane, those quantities no longer depend on the
range error. Frames: any one frame for all arguments (body FRD or target ENU), metres.
"""

from __future__ import annotations

import numpy as np

#: Beams closer than arccos(MIN_COS) (about 87°) to a plane keep the sounding itself.
MIN_COS = 0.05


def beam_meets_plane(y: np.ndarray, normal: np.ndarray, r: np.ndarray,
                     min_cos: float = MIN_COS) -> np.ndarray:
    """Vectors (n, 3) m from the beam's start to where it meets the plane.

    *y* (n, 3): from the beam's start (the multibeam head) to the sounding; *normal* (3,)
    or (n, 3): the plane's unit normal; *r* (n,): the sounding's signed distance to the
    plane. The sounding moves along its beam by ``r / cos``; a grazing beam
    (|cos| < *min_cos*) keeps ``y``.
    """
    length = np.linalg.norm(y, axis=1)
    unit = y / np.maximum(length, 1e-12)[:, None]
    cos = unit @ normal if np.ndim(normal) == 1 else np.einsum("ij,ij->i", unit, normal)
    ok = np.abs(cos) >= min_cos
    along = np.where(ok, r / np.where(ok, cos, 1.0), 0.0)
    return y - along[:, None] * unit


def sounding_points(ctx, idx: np.ndarray, r_m: np.ndarray, lever: np.ndarray,
                    plane=None) -> np.ndarray:
    """Target ENU points (n, 3) m of the soundings *idx* of a
    :class:`~.georef.GeorefContext` with boresight *r_m* and lever (body FRD, m); with a
    *plane* (``normal``, ``d``), where their beams meet it instead."""
    p = ctx.ping[idx]
    y = ctx.x_m[idx] @ r_m.T
    if plane is not None:
        a = np.einsum("nji,j->ni", ctx.rot[p], plane.normal)       # normal in body frame
        r = ctx.origin[p] @ plane.normal + np.einsum("ni,ni->n", a, y + lever) - plane.d
        y = beam_meets_plane(y, a, r)
    return ctx.origin[p] + np.einsum("nij,nj->ni", ctx.rot[p], y + lever)
