"""Vectorised georeferencing of multibeam soundings into the target ENU frame.

``p_enu = ins_enu(t) + C · R_b(t) · (R_m · x_m + l_b)`` (``formats.md``; seed eq. [0034]
with the pool's local ENU frame in place of ECEF), where ``R_m`` is the boresight
(sensor -> body FRD), ``l_b`` the lever arm (body FRD, m), ``R_b`` the INS attitude
(body FRD -> NED) and ``C`` the NED -> ENU swap. The INS is interpolated at the ping time:
position linearly, attitude by Slerp. Pings that fall inside an INS time gap (or outside
the INS time span) are dropped and counted, never interpolated.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial.transform import Rotation, Slerp

from hydrosync_core.errors import InputError
from hydrosync_core.rotations import C_NED_TO_ENU, euler_zyx_angles, euler_zyx_matrix

__all__ = ["C_NED_TO_ENU", "GeorefContext", "boresight_angles", "boresight_matrix"]

def boresight_matrix(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """R_m = Rz(yaw)·Ry(pitch)·Rx(roll), radians; sensor frame -> body FRD."""
    return euler_zyx_matrix(roll, pitch, yaw)


def boresight_angles(matrix: np.ndarray) -> tuple[float, float, float]:
    """(roll, pitch, yaw) radians of a boresight matrix (inverse of :func:`boresight_matrix`)."""
    return euler_zyx_angles(matrix)


@dataclass(frozen=True)
class GeorefContext:
    """Per-ping INS state at the kept pings and the soundings that belong to them.

    Attributes
    ----------
    x_m : (N, 3) sounding vectors in the multibeam frame (FRD, m), kept soundings only.
    ping : (N,) index of each kept sounding's ping in ``origin``/``rot``.
    origin : (P, 3) INS reference point at each kept ping time, target ENU, m.
    rot : (P, 3, 3) ``C · R_b`` at each kept ping time (body FRD -> ENU).
    keep : (M,) mask over the input soundings: True where georeferenced.
    dropped_pings, dropped_soundings : counts of pings/soundings in INS gaps or outside.
    ping_time : (P,) time (s) of each kept ping (None when built by hand); merged passes
        are shifted apart (:func:`merge`).
    """

    x_m: np.ndarray
    ping: np.ndarray
    origin: np.ndarray
    rot: np.ndarray
    keep: np.ndarray
    dropped_pings: int
    dropped_soundings: int
    ping_time: np.ndarray | None = None
    #: First ping index of each pass when several passes were merged (:func:`merge`).
    pass_start: np.ndarray | None = None

    @property
    def mean_rot(self) -> np.ndarray:
        """Mean body -> ENU rotation over the kept pings (chordal mean)."""
        return Rotation.from_matrix(self.rot).mean().as_matrix()


def ins_gaps(time: np.ndarray, max_gap_s: float | None = None) -> np.ndarray:
    """Mask over INS intervals ``[t_i, t_i+1]`` that are gaps (longer than *max_gap_s*).

    Default threshold: 3 × the median sampling interval.
    """
    dt = np.diff(time)
    limit = 3.0 * float(np.median(dt)) if max_gap_s is None else max_gap_s
    return dt > limit


def prepare(mbes: dict, ins: dict, max_gap_s: float | None = None,
            source: str = "ins") -> GeorefContext:
    """Interpolate the INS at the ping times and build a :class:`GeorefContext`.

    Parameters
    ----------
    mbes : dict with ``time`` (s), ``x, y, z`` (m, sensor FRD), time-sorted.
    ins : dict with ``time`` (s), ``e, n, u`` (m, ENU), ``roll, pitch, heading`` (deg).
    max_gap_s : INS interval above which the INS is not interpolated (default 3× median).
    """
    t_ins = np.asarray(ins["time"], dtype=float)
    if len(t_ins) < 2:
        raise InputError(source, "the INS trajectory needs at least 2 epochs")
    if np.any(np.diff(t_ins) <= 0):
        raise InputError(source, "INS times must be strictly increasing (sorted, no "
                         "duplicates)", field="time")
    ping_t, ping_of = np.unique(np.asarray(mbes["time"], dtype=float), return_inverse=True)
    # Locate each ping in the INS time series; j is the interval [t_j, t_j+1].
    j = np.searchsorted(t_ins, ping_t, side="right") - 1
    inside = (ping_t >= t_ins[0]) & (ping_t <= t_ins[-1])
    j = np.clip(j, 0, len(t_ins) - 2)
    gap = ins_gaps(t_ins, max_gap_s)
    exact = np.isin(ping_t, t_ins)
    ok_ping = inside & (~gap[j] | exact)
    if not ok_ping.any():
        raise InputError(source, "no multibeam ping falls inside the INS time span "
                         "(outside gaps); check the time scales")
    tp = ping_t[ok_ping]
    # Linear interpolation of the position (ENU, m).
    origin = np.column_stack([np.interp(tp, t_ins, np.asarray(ins[k], float))
                              for k in ("e", "n", "u")])
    # Slerp of the attitude: R_b = Rz(heading)·Ry(pitch)·Rx(roll), body FRD -> NED.
    att = Rotation.from_euler("ZYX", np.deg2rad(np.column_stack(
        [ins["heading"], ins["pitch"], ins["roll"]])))
    r_b = Slerp(t_ins, att)(tp).as_matrix()
    rot = np.einsum("ij,pjk->pik", C_NED_TO_ENU, r_b)
    new_index = np.cumsum(ok_ping) - 1
    keep = ok_ping[ping_of]
    x_m = np.column_stack([mbes["x"], mbes["y"], mbes["z"]])[keep]
    return GeorefContext(
        x_m=x_m, ping=new_index[ping_of[keep]], origin=origin, rot=rot, keep=keep,
        dropped_pings=int((~ok_ping).sum()), dropped_soundings=int((~keep).sum()),
        ping_time=tp,
    )


#: Ping-time gap (s) put between merged passes: far beyond any INS correlation time or
#: ping block, so no error model links two passes (they are independent recordings).
PASS_SEPARATION_S = 1.0e4


def merge(contexts: list[GeorefContext]) -> GeorefContext:
    """One context holding several passes (each prepared with its own INS).

    Soundings and pings are concatenated (ping indices offset). Each pass's ping times are
    shifted to start :data:`PASS_SEPARATION_S` after the previous pass ends, so the times
    stay increasing (``ins_cov``) and no ping block spans two passes (``block_sigma``);
    ``pass_start`` holds the first ping index of each pass.
    """
    if len(contexts) == 1:
        return contexts[0]
    x_m, ping, origin, rot, keep, times, starts = [], [], [], [], [], [], []
    n_ping, t_end = 0, None
    for c in contexts:
        x_m.append(c.x_m)
        ping.append(c.ping + n_ping)
        origin.append(c.origin)
        rot.append(c.rot)
        keep.append(c.keep)
        tp = c.ping_time if c.ping_time is not None else np.arange(len(c.origin), dtype=float)
        shift = 0.0 if t_end is None else t_end + PASS_SEPARATION_S - tp[0]
        times.append(tp + shift)
        t_end = float(times[-1][-1])
        starts.append(n_ping)
        n_ping += len(c.origin)
    return GeorefContext(
        x_m=np.concatenate(x_m), ping=np.concatenate(ping), origin=np.concatenate(origin),
        rot=np.concatenate(rot), keep=np.concatenate(keep),
        dropped_pings=sum(c.dropped_pings for c in contexts),
        dropped_soundings=sum(c.dropped_soundings for c in contexts),
        ping_time=np.concatenate(times), pass_start=np.array(starts, dtype=np.int64))


def georeference(ctx: GeorefContext, r_m: np.ndarray, lever: np.ndarray,
                 select: np.ndarray | None = None, chunk: int = 500_000) -> np.ndarray:
    """ENU coordinates (n, 3) m of the kept soundings (or the subset *select*).

    ``p = o + (C R_b)(R_m x_m + l_b)`` evaluated in chunks to bound memory.
    """
    idx = np.arange(len(ctx.x_m)) if select is None else np.asarray(select)
    out = np.empty((len(idx), 3))
    for start in range(0, len(idx), chunk):
        sl = idx[start:start + chunk]
        body = ctx.x_m[sl] @ r_m.T + lever
        p = ctx.ping[sl]
        out[start:start + chunk] = ctx.origin[p] + np.einsum("nij,nj->ni", ctx.rot[p], body)
    return out


def sensor_heads(ctx: GeorefContext, lever: np.ndarray) -> np.ndarray:
    """ENU position (n, 3) m of the multibeam head at each kept sounding's ping,
    ``o + (C R_b) l_b``, where its beam starts (computed once per ping, then repeated for
    its soundings)."""
    per_ping = ctx.origin + ctx.rot @ np.asarray(lever, float)
    return per_ping[ctx.ping]
