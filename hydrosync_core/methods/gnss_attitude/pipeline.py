"""From per-antenna ECEF positions to heading, pitch and roll: screening and solving.

Steps per epoch (epochs matched across the antenna files by time, rounded to
``epoch_rounding_s``):

1. antennas whose solution quality is not accepted (``min_quality``) are left out;
2. the array position (mean of the antennas) gives latitude B and longitude L, and the
   antenna positions are rotated from ECEF to the local NED frame there (Liu et al.);
3. baseline-length screening: while some measured antenna distance differs from the
   known body-frame distance by more than ``length_tolerance_m``, the antenna involved
   in most such pairs is dropped;
4. epochs with three or more antennas left are solved by all three estimators
   (:mod:`.solve`): Wahba (closed form, also the LSQ initial value), LSQ (weighted,
   iterated, with covariance) and the direct method (three antennas), whose standard
   deviations come from linear propagation of the antennas' position covariance.

Angles are returned in degrees (heading 0–360°, pitch ±90°, roll ±180°), times as the
files' GPS time of week (s) and continuous GPS seconds.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from itertools import combinations

import numpy as np

from hydrosync_core.errors import InputError
from hydrosync_core.geodesy import ecef_to_geodetic, ecef_to_ned_matrix
from hydrosync_core.methods.gnss_attitude import solve
from hydrosync_core.methods.gnss_attitude.params import GnssAttitudeParams
from hydrosync_core.progress import check_cancel, report
from hydrosync_core.rotations import wrap_pi

QUALITY_LIMIT = {"fixed": 1, "float": 2, "any": 7}
CHUNK = 50_000


@dataclass
class Track:
    """One antenna's positions.

    Attributes
    ----------
    gps_s : ndarray (n,)
        Continuous GPS seconds (s since 1980-01-06 on the file's scale).
    ecef : ndarray (n, 3)
        ECEF positions (m).
    q : ndarray (n,) of int
        RTKLIB quality flag (1 fixed, 2 float, …).
    cov_ned : ndarray (n, 3, 3) or None
        Position covariance in NED (m²); None → a-priori σ.
    week_based : bool
        True when *gps_s* are GPS seconds (``.pos``/``.geo`` files): the solution's
        ``time`` is then the time of week. False for times on another continuous scale
        (the CSV's ``time`` column), which are reported as given.
    """

    gps_s: np.ndarray
    ecef: np.ndarray
    q: np.ndarray
    cov_ned: np.ndarray | None = None
    week_based: bool = True


@dataclass
class MethodSolution:
    """One estimator's attitude per epoch (NaN where it has no solution).

    ``angles_deg`` (E, 3) and ``std_deg`` (E, 3) are in the order heading, pitch, roll.
    """

    angles_deg: np.ndarray
    std_deg: np.ndarray
    extra: dict[str, np.ndarray] = field(default_factory=dict)


@dataclass
class ArraySolution:
    """All epochs of an array run.

    Attributes
    ----------
    time : ndarray (E,)
        GPS time of week (s); the input times as given when they are not GPS seconds
        (:attr:`Track.week_based`).
    gps_s : ndarray (E,)
        Continuous GPS seconds.
    names : list of str
        Antenna names (column order of *used*).
    used : ndarray (E, K) of bool
        Antennas used per epoch (after quality and length screening).
    n_antennas : ndarray (E,) of int
    methods : dict of str to MethodSolution
        ``"lsq"``, ``"wahba"``, ``"direct"``.
    pairs : list of str
        ``"A1-A2"`` names of the antenna pairs of *length_residual_m*.
    length_residual_m : ndarray (E, P)
        Measured minus known antenna distance (m) for antennas of accepted quality
        (NaN otherwise).
    counts : dict
        Screening counts (see :func:`solve_array`).
    array_llh : tuple of float
        Mean latitude, longitude (deg) and height (m) of the array.
    """

    time: np.ndarray
    gps_s: np.ndarray
    names: list[str]
    used: np.ndarray
    n_antennas: np.ndarray
    methods: dict[str, MethodSolution]
    pairs: list[str]
    length_residual_m: np.ndarray
    counts: dict
    array_llh: tuple[float, float, float]

    @property
    def solved(self) -> np.ndarray:
        return self.n_antennas >= 3


def _apriori_cov(p: GnssAttitudeParams) -> np.ndarray:
    return np.diag([p.sigma_horizontal_m**2, p.sigma_horizontal_m**2, p.sigma_vertical_m**2])


def match_epochs(tracks: Mapping[str, Track], rounding_s: float):
    """Common epoch grid: (gps_s (E,), index (K, E) into each track or −1, duplicates)."""
    keys = {n: np.round(t.gps_s / rounding_s).astype(np.int64) for n, t in tracks.items()}
    grid = np.unique(np.concatenate(list(keys.values())))
    index, dups = {}, {}
    for n, k in keys.items():
        first = np.unique(k, return_index=True)[1]
        dups[n] = int(k.size - first.size)
        pos = np.full(grid.size, -1)
        pos[np.searchsorted(grid, k[first])] = first
        index[n] = pos
    return grid * rounding_s, index, dups


def screen_lengths(ned: np.ndarray, ok: np.ndarray, body: np.ndarray, tol: float):
    """Drop, per epoch, antennas whose distances disagree with the body geometry.

    Parameters
    ----------
    ned : (E, K, 3) positions (m, any common origin); ok : (E, K) bool; body : (K, 3) m.

    Returns
    -------
    (used (E, K) bool, residual (E, P) m for the pairs of ``combinations(range(K), 2)``)
    """
    K = body.shape[0]
    pairs = list(combinations(range(K), 2))
    known = np.array([np.linalg.norm(body[i] - body[j]) for i, j in pairs])
    meas = np.stack([np.linalg.norm(ned[:, i] - ned[:, j], axis=-1) for i, j in pairs], -1)
    resid = meas - known
    both = np.stack([ok[:, i] & ok[:, j] for i, j in pairs], -1)
    resid = np.where(both, resid, np.nan)
    used = ok.copy()
    for _ in range(K):
        live = np.stack([used[:, i] & used[:, j] for i, j in pairs], -1)
        bad = live & (np.abs(np.nan_to_num(resid)) > tol)
        if not bad.any():
            break
        votes = np.zeros(used.shape)
        size = np.zeros(used.shape)
        for c, (i, j) in enumerate(pairs):
            votes[:, i] += bad[:, c]
            votes[:, j] += bad[:, c]
            size[:, i] += np.where(bad[:, c], np.abs(np.nan_to_num(resid[:, c])), 0.0)
            size[:, j] += np.where(bad[:, c], np.abs(np.nan_to_num(resid[:, c])), 0.0)
        rows = np.flatnonzero(bad.any(axis=1))
        score = votes[rows] * 1e6 + size[rows]
        worst = np.argmax(np.where(used[rows], score, -1.0), axis=1)
        used[rows, worst] = False
    return used, resid


def _triplet(names: list[str], body: np.ndarray, avail: np.ndarray,
             chosen: tuple[str, str, str] | None) -> tuple[int, int, int] | None:
    """Antenna indices (1, 2, 3) of the direct method for one availability pattern."""
    if chosen is not None:
        idx = tuple(names.index(n) for n in chosen)
        return idx if all(avail[i] for i in idx) else None  # type: ignore[return-value]
    cand = [i for i in range(len(names)) if avail[i]]
    best, best_area = None, 0.0
    for a, b, c in combinations(cand, 3):
        area = np.linalg.norm(np.cross(body[b] - body[a], body[c] - body[a]))
        if area > best_area + 1e-12:
            best, best_area = (a, b, c), area
    if best is None:
        return None
    a, b, c = best
    # the longest side is baseline 1 -> 2 (Liu et al.: the heading/pitch baseline)
    sides = {(a, b): c, (a, c): b, (b, c): a}
    (i, j), k = max(sides.items(), key=lambda s: np.linalg.norm(body[s[0][1]] - body[s[0][0]]))
    return i, j, k


def _direct_with_std(ned: np.ndarray, cov: np.ndarray, body: np.ndarray, tri):
    """Direct-method angles (rad, (n, 3) roll/pitch/heading) and their covariance."""
    i, j, k = tri
    b12, b13 = body[j] - body[i], body[k] - body[i]
    x = np.concatenate([ned[:, j] - ned[:, i], ned[:, k] - ned[:, i]], axis=1)  # (n, 6)

    def angles(v):
        R = solve.direct_three(v[:, :3], v[:, 3:], b12, b13)
        return np.stack(solve.matrix_angles(R), axis=-1), R

    a0, R0 = angles(x)
    h = 1e-5
    J = np.empty(x.shape[:1] + (3, 6))
    for c in range(6):
        d = np.zeros(6)
        d[c] = h
        ap, _ = angles(x + d)
        am, _ = angles(x - d)
        J[:, :, c] = wrap_pi(ap - am) / (2 * h)
    C = np.zeros((x.shape[0], 6, 6))
    C[:, :3, :3] = cov[:, i] + cov[:, j]
    C[:, 3:, 3:] = cov[:, i] + cov[:, k]
    C[:, :3, 3:] = C[:, 3:, :3] = cov[:, i]
    return a0, R0, J @ C @ np.swapaxes(J, -1, -2)


def _to_deg(angles_rad: np.ndarray, cov: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(heading, pitch, roll) degrees and their std from (roll, pitch, heading) rad."""
    ang = np.degrees(angles_rad[:, [2, 1, 0]])
    std = np.degrees(np.sqrt(np.clip(np.diagonal(cov, axis1=-2, axis2=-1), 0, None)))[:, [2, 1, 0]]
    return ang, std


def solve_array(tracks: Mapping[str, Track], antennas: Mapping[str, list[float]],
                params: GnssAttitudeParams, progress=None, cancel=None) -> ArraySolution:
    """Screen and solve every epoch of an antenna array.

    Parameters
    ----------
    tracks : mapping of antenna name to :class:`Track`
        One per antenna file; every name must be in *antennas*.
    antennas : mapping of name to [x, y, z]
        Body-frame (FRD) coordinates (m).
    params : GnssAttitudeParams
    progress, cancel : optional
        Progress callback and cancel token (checked between chunks).

    Returns
    -------
    ArraySolution
        ``counts`` holds ``epochs`` (all matched epochs), ``solved``, ``too_few_antennas``,
        ``with_dropped_antenna``, ``cov_fallback`` (solved epochs where some used
        antenna's file covariance was not positive definite and the a-priori σ replaced
        it), per antenna ``present``, ``cov_fallback`` (rows whose covariance fell back),
        ``not_accepted_quality``, ``length_rejected``, ``used``, ``duplicates``, and the
        gaps between solved epochs
        (``gaps``, ``longest_gap_s``, ``median_interval_s``).

    Raises
    ------
    InputError
        Fewer than three antennas with data, a track without antenna coordinates, no
        epoch with three accepted antennas.
    """
    names = _array_names(tracks, antennas, params)
    body = np.array([antennas[n] for n in names], float)
    report(progress, 0.0, "matching epochs")
    check_cancel(cancel)
    gps_s, index, dups = match_epochs({n: tracks[n] for n in names}, params.epoch_rounding_s)
    ecef, q, cov, fallback = _gather(tracks, names, index, params)
    present = q > 0
    ok = present & (q <= QUALITY_LIMIT[params.min_quality])
    ned, lat, lon, hgt = _local_level(ecef, ok)
    report(progress, 0.05, "screening baseline lengths")
    check_cancel(cancel)
    used, resid = screen_lengths(ned, ok, body, params.length_tolerance_m)
    n_used = used.sum(axis=1)
    solved = n_used >= 3
    if not solved.any():
        raise InputError(None, f"no epoch has three antennas with accepted quality "
                         f"({params.min_quality}) and consistent baseline lengths "
                         f"(of {gps_s.size} epochs, {int(ok.sum(1).max(initial=0))} antennas "
                         "at most accepted)", field="min_quality")
    methods = _solve_epochs(ned, cov, body, names, used, solved, params, progress, cancel)
    report(progress, 0.97, "counting")
    counts = _counts(gps_s, names, present, ok, used, solved, fallback, methods, dups, params)
    week_based = all(tracks[n].week_based for n in names)
    week = np.floor(gps_s / 604800.0) if week_based else np.zeros_like(gps_s)
    K = len(names)
    pairs = [f"{names[i]}-{names[j]}" for i, j in combinations(range(K), 2)]
    llh = (float(np.nanmean(lat)), float(np.nanmean(lon)), float(np.nanmean(hgt)))
    report(progress, 1.0, "attitude solved")
    return ArraySolution(gps_s - week * 604800.0, gps_s, names, used & solved[:, None],
                         np.where(solved, n_used, 0), methods, pairs, resid, counts, llh)


def _array_names(tracks: Mapping[str, Track], antennas: Mapping[str, list[float]],
                 params: GnssAttitudeParams) -> list[str]:
    """The antennas with both positions and body coordinates, in the coordinates' order;
    InputError for an unknown track, fewer than three antennas or a direct-method antenna
    without positions."""
    unknown = [n for n in tracks if n not in antennas]
    if unknown:
        raise InputError(unknown[0], f"no antenna '{unknown[0]}' in the antenna coordinates "
                         f"(known: {', '.join(antennas)})", field="antennas")
    names = [n for n in antennas if n in tracks]
    if len(names) < 3:
        raise InputError(None, f"positions of {len(names)} antenna(s) given: attitude needs "
                         "at least three", field="pos")
    chosen = params.direct_triplet
    if chosen is not None:
        missing = [n for n in chosen if n not in names]
        if missing:
            raise InputError(None, f"direct-method antenna '{missing[0]}' has no positions",
                             field="direct_antennas")
    return names


def _gather(tracks: Mapping[str, Track], names: list[str], index: dict,
            params: GnssAttitudeParams):
    """Per epoch and antenna: ECEF position (m, NaN where absent), quality (0 absent),
    the NED position covariance (m², file or a-priori) and where the file's covariance
    was not positive definite and the a-priori one replaced it."""
    E, K = next(iter(index.values())).size, len(names)
    ecef = np.full((E, K, 3), np.nan)
    q = np.zeros((E, K), np.int16)
    cov = np.broadcast_to(_apriori_cov(params), (E, K, 3, 3)).copy()
    fallback = np.zeros((E, K), bool)
    for k, n in enumerate(names):
        t, pos = tracks[n], index[n]
        have = pos >= 0
        ecef[have, k] = t.ecef[pos[have]]
        q[have, k] = t.q[pos[have]]
        if params.weights == "file" and t.cov_ned is not None:
            c = t.cov_ned[pos[have]]
            good = np.all(np.isfinite(c), axis=(-2, -1))
            good[good] = np.all(np.linalg.eigvalsh(c[good]) > 0, axis=-1)
            sel = np.flatnonzero(have)[good]
            cov[sel, k] = c[good]
            fallback[np.flatnonzero(have)[~good], k] = True
    return ecef, q, cov, fallback


def _local_level(ecef: np.ndarray, ok: np.ndarray):
    """NED positions (E, K, 3) about each epoch's centre of the accepted antennas, and the
    centre's latitude, longitude (deg) and height (m) (NaN where none is accepted)."""
    any_ok = ok.any(axis=1)
    centre = np.where(ok[..., None], ecef, 0.0).sum(axis=1) / np.maximum(ok.sum(1), 1)[:, None]
    centre[~any_ok] = np.nan
    lat, lon, hgt = ecef_to_geodetic(centre)
    C = ecef_to_ned_matrix(np.nan_to_num(lat), np.nan_to_num(lon))
    ned = np.einsum("eij,ekj->eki", C, np.nan_to_num(ecef - centre[:, None, :]))
    return ned, lat, lon, hgt


def _solve_epochs(ned, cov, body, names, used, solved, params, progress, cancel) -> dict:
    """The three estimators on every solved epoch, in chunks of epochs that share one set
    of used antennas (one design per set): ``{"lsq", "wahba", "direct"}`` solutions."""
    E, K = used.shape
    chosen = params.direct_triplet
    methods = {m: MethodSolution(np.full((E, 3), np.nan), np.full((E, 3), np.nan))
               for m in ("lsq", "wahba", "direct")}
    methods["lsq"].extra = {"iterations": np.zeros(E, np.int16),
                            "converged": np.zeros(E, bool), "sigma0": np.full(E, np.nan)}
    patterns = (used * (1 << np.arange(K))).sum(axis=1)
    todo = [(pat, np.flatnonzero((patterns == pat) & solved))
            for pat in np.unique(patterns[solved])]
    total = max(1, int(solved.sum()))
    done = 0
    thr = np.radians(params.convergence_deg)
    for pat, rows in todo:
        avail = np.array([(pat >> k) & 1 for k in range(K)], bool)
        members = np.flatnonzero(avail)
        ref, others = members[0], members[1:]
        body_b = body[others] - body[ref]
        tri = _triplet(names, body, avail, chosen)
        for start in range(0, rows.size, CHUNK):
            check_cancel(cancel)
            report(progress, 0.1 + 0.85 * done / total,
                   f"solving epochs ({done} of {total})")
            r = rows[start:start + CHUNK]
            nav = ned[r][:, others] - ned[r][:, [ref]]
            cv = cov[r][:, members]
            W = solve.baseline_weight(cv, 0)
            tr = np.trace(cv, axis1=-2, axis2=-1)
            w = 3.0 / (tr[:, :1] + tr[:, 1:])
            Rw = solve.wahba(nav, body_b, w)
            res = solve.lsq(nav, body_b, W, Rw, thr, params.max_iterations)
            ang, std = _to_deg(res.angles, res.cov)
            methods["lsq"].angles_deg[r], methods["lsq"].std_deg[r] = ang, std
            methods["lsq"].extra["iterations"][r] = res.iterations
            methods["lsq"].extra["converged"][r] = res.converged
            methods["lsq"].extra["sigma0"][r] = res.sigma0
            aw = np.stack(solve.matrix_angles(Rw), axis=-1)
            ang, std = _to_deg(aw, solve.formal_covariance(Rw, body_b, W))
            methods["wahba"].angles_deg[r], methods["wahba"].std_deg[r] = ang, std
            if tri is not None:
                ad, _, cd = _direct_with_std(ned[r], cov[r], body, tri)
                ang, std = _to_deg(ad, cd)
                methods["direct"].angles_deg[r], methods["direct"].std_deg[r] = ang, std
            done += r.size
    return methods


def _counts(gps_s, names, present, ok, used, solved, fallback, methods, dups, params) -> dict:
    """The bookkeeping of :class:`ArraySolution` ``counts`` (see :func:`solve_array`)."""
    n_used = used.sum(axis=1)
    dt = np.diff(gps_s[solved])
    median_dt = float(np.median(dt)) if dt.size else float("nan")
    gaps = dt > params.gap_factor * median_dt if dt.size else np.zeros(0, bool)
    return {
        "epochs": int(gps_s.size), "solved": int(solved.sum()),
        "too_few_antennas": int((~solved).sum()),
        "with_dropped_antenna": int((solved & (n_used < ok.sum(1))).sum()),
        "lsq_not_converged": int((solved & ~methods["lsq"].extra["converged"]).sum()),
        "direct_solved": int(np.isfinite(methods["direct"].angles_deg[:, 0]).sum()),
        "gaps": int(gaps.sum()), "longest_gap_s": float(dt.max()) if dt.size else 0.0,
        "median_interval_s": median_dt,
        "cov_fallback": int((fallback & used & solved[:, None]).any(axis=1).sum()),
        "antennas": {n: {"present": int(present[:, k].sum()),
                         "cov_fallback": int(fallback[:, k].sum()),
                         "not_accepted_quality": int((present[:, k] & ~ok[:, k]).sum()),
                         "length_rejected": int((ok[:, k] & ~used[:, k]).sum()),
                         "used": int((used[:, k] & solved).sum()),
                         "duplicates": dups[n]} for k, n in enumerate(names)},
    }


def circular_std_deg(a_deg: np.ndarray) -> tuple[float, float]:
    """Circular mean (deg, 0–360) and standard deviation (deg) of headings."""
    a = np.radians(a_deg)
    mean = np.arctan2(np.mean(np.sin(a)), np.mean(np.cos(a)))
    d = wrap_pi(a - mean)
    return float(np.degrees(mean) % 360.0), float(np.degrees(np.std(d, ddof=1)))


def statistics(sol: ArraySolution, start: float | None = None,
               end: float | None = None) -> dict:
    """Scatter of each method's angles over [start, end] (time of week, s).

    Returns ``{method: {"epochs": n, "heading": {"mean", "std", "predicted"}, …}}`` in
    degrees: ``std`` is the measured standard deviation (heading circular), ``predicted``
    the RMS of the per-epoch formal standard deviations, ``predicted`` beside ``std`` is
    the precision check of Liu et al.'s static-period table.
    """
    return interval_statistics(sol.time, {name: (m.angles_deg, m.std_deg)
                                          for name, m in sol.methods.items()}, start, end)


def interval_statistics(time: np.ndarray, methods: Mapping[str, tuple[np.ndarray, np.ndarray]],
                        start: float | None = None, end: float | None = None) -> dict:
    """:func:`statistics` from arrays: *methods* maps a name to (angles (E, 3), std (E, 3))
    in degrees, order heading, pitch, roll; *time* (E,) on the scale of *start*/*end*.

    Used to recompute the table for another static interval from the stored per-method
    tables, without solving again.
    """
    time = np.asarray(time, float)
    sel = np.ones(time.size, bool)
    if start is not None:
        sel &= time >= start
    if end is not None:
        sel &= time <= end
    out = {}
    for name, (angles_deg, std_deg) in methods.items():
        m = MethodSolution(np.asarray(angles_deg, float), np.asarray(std_deg, float))
        good = sel & np.isfinite(m.angles_deg[:, 0])
        entry: dict = {"epochs": int(good.sum())}
        for c, angle in enumerate(("heading", "pitch", "roll")):
            v = m.angles_deg[good, c]
            if v.size < 2:
                entry[angle] = {"mean": None, "std": None, "predicted": None}
                continue
            if angle == "heading":
                mean, std = circular_std_deg(v)
            elif angle == "roll":
                mean_r, std = circular_std_deg(v)
                mean = (mean_r + 180.0) % 360.0 - 180.0
            else:
                mean, std = float(np.mean(v)), float(np.std(v, ddof=1))
            pred = float(np.sqrt(np.nanmean(m.std_deg[good, c] ** 2)))
            entry[angle] = {"mean": mean, "std": std, "predicted": pred}
        out[name] = entry
    return out
