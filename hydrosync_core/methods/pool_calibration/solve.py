"""The solving half of the pool calibration: seed angles, seed lever arm, joint LSQ.

Runs on a :class:`~.estimator.Segmentation` (inputs as documented in :mod:`.estimator`); the result
is a :class:`~.result.PoolResult`.

Every face the multibeam sees is compared with its reference plane (:mod:`.twins`): its
own laser plane when it crosses the water, its above-water twin's laser plane moved by
the design translation when it lies below water. The multibeam points of each face are
those within a refined band around the aligned setup (:mod:`.align`), the same for both
solutions; the joint adjustment is repeated once on the points re-selected around its own
solution.

Undetermined parameters (never a value fitted from insufficient geometry): a parameter
that no face can determine (a singular normal matrix; the patent's seed also needs a
below-water block top with a twin for lever_z, the joint adjustment only needs the data to
fix it) or whose σ from the data exceeds the accuracy of the coarse setup
keeps its coarse value, gets a NaN σ and a named reason (``PoolResult.undetermined``);
the coarse error of such a parameter is propagated into the σ of the others. A parameter
whose σ exceeds ``max_sigma_deg``/``max_sigma_m`` is flagged (``PoolResult.flagged``).
"""

from __future__ import annotations

import numpy as np

from hydrosync_core.methods.pool_calibration import georef
from hydrosync_core.methods.pool_calibration.align import structural_fix
from hydrosync_core.methods.pool_calibration.joint import NAMES, adjust, correlation
from hydrosync_core.methods.pool_calibration.lever_arm import lever_offsets
from hydrosync_core.methods.pool_calibration.params import PoolParams
from hydrosync_core.methods.pool_calibration.planes import angle_deg, fit_plane
from hydrosync_core.methods.pool_calibration.result import (
    FaceRow,
    JointSolution,
    PoolResult,
    SeedSolution,
)
from hydrosync_core.methods.pool_calibration.roles import PARAMETER_ROLES
from hydrosync_core.methods.pool_calibration.seed_iteration import iterate_angles
from hydrosync_core.methods.pool_calibration.segment import segment_cloud
from hydrosync_core.progress import check_cancel, report, sub_progress


def _angles(r_m) -> dict:
    r, p, y = np.degrees(georef.boresight_angles(r_m))
    return {"roll": float(r), "pitch": float(p), "yaw": float(y)}


def _lever(v) -> dict:
    return {k: float(x) for k, x in zip("xyz", v, strict=True)}


def _matrix(angles_deg: dict) -> np.ndarray:
    return georef.boresight_matrix(*np.deg2rad([angles_deg[k] for k in ("roll", "pitch",
                                                                        "yaw")]))


def _vector(lever: dict) -> np.ndarray:
    return np.array([lever[k] for k in "xyz"], dtype=float)


def _joint_obs(seg, mfaces, min_points):
    """Reference plane per face: its own laser plane or its twin's, moved (seg.refs)."""
    return {name: (idx, seg.refs[name].plane) for name, idx in mfaces.items()
            if len(idx) >= min_points and name in seg.refs}


#: What reduces each σ-budget source (the advice of a flagged parameter).
REMEDY = {
    "data": "more passes, slower, at other ranges and on lines crossing the wall at about "
            "±15°",
    "build": "survey the as-built below-water blocks (smaller build tolerance)",
    "reference": "a denser laser scan of the above-water faces",
    "ins": "a more accurate INS",
    "held": "passes that determine the held parameters",
}


def _budget(fit) -> dict[str, dict[str, float | None]]:
    """σ budget of the joint fit in user units (° for angles, m for the lever arm)."""
    out = {}
    scale = np.array([np.degrees(1.0)] * 3 + [1.0] * 3)
    for source, sig in fit.budget.items():
        out[source] = {n: (None if not np.isfinite(v) else float(v * f))
                       for n, v, f in zip(NAMES, sig, scale, strict=True)}
    return out


def _flags(cov, fixed, p, budget: dict | None = None) -> dict[str, str]:
    out = {}
    sig = np.sqrt(np.clip(np.nan_to_num(np.diag(cov)), 0, None))
    for k, name in enumerate(NAMES):
        if name in fixed:
            continue
        s, lim, unit = (np.degrees(sig[k]), p.max_sigma_deg, "°") if k < 3 else \
            (sig[k], p.max_sigma_m, " m")
        if s > lim:
            out[name] = f"σ = {s:.4g}{unit} exceeds {lim:g}{unit}: poorly determined"
            shares = {src: v[name] ** 2 for src, v in (budget or {}).items()
                      if v.get(name) is not None}
            total = sum(shares.values())
            if total > 0:
                top = max(shares, key=shares.get)
                out[name] += (f"; {100 * shares[top] / total:.0f} % of its variance from "
                              f"{top} (helps: {REMEDY[top]})")
                out[name] += "; " + _passes_needed(shares, lim, unit)
    return out


#: Budget sources that average down with more passes like these (independent noise and
#: INS errors of a few seconds' correlation); the others are fixed by the target and setup.
SCALABLE = ("data", "ins")


def _passes_needed(shares: dict[str, float], limit: float, unit: str) -> str:
    """How many times the passes (soundings) would bring σ to *limit*, or why none can.

    *shares* are the variances per source (in the unit of *limit*, squared)."""
    scalable = sum(v for k, v in shares.items() if k in SCALABLE)
    fixed = sum(v for k, v in shares.items() if k not in SCALABLE)
    if fixed >= limit**2:
        worst = max((k for k in shares if k not in SCALABLE), key=shares.get)
        return (f"more passes cannot bring it to {limit:g}{unit}: the {worst} part alone "
                f"gives {np.sqrt(fixed):.3g}{unit}")
    factor = scalable / (limit**2 - fixed)
    return f"about {factor:.1f}× the passes like these would bring it to {limit:g}{unit}"


def _corr_warnings(corr, p) -> list[str]:
    out = []
    for i in range(6):
        for j in range(i + 1, 6):
            if abs(corr[i, j]) > p.max_corr:
                out.append(f"joint adjustment: {NAMES[i]} and {NAMES[j]} strongly correlated "
                           f"(r = {corr[i, j]:+.3f}); add passes at other ranges/headings")
    return out


def _resegment(seg, p, r_m, lever, cancel) -> dict[str, np.ndarray]:
    """Multibeam face indices re-cropped with tight tolerances around (r_m, lever)."""
    pts = georef.georeference(seg.ctx, r_m, lever)
    mseg = segment_cloud(pts, list(seg.design.values()), seg.water_level, "below",
                         tol=p.refine_tol_m, margin=p.face_margin_m,
                         water_margin=p.water_margin_m, ransac_m=p.refine_ransac_m,
                         dbscan_eps=p.dbscan_mbes_m, max_points=p.max_points_per_face,
                         band_sigma=p.refine_band_sigma,
                         heads=georef.sensor_heads(seg.ctx, lever), cancel=cancel)
    return {n: s.indices for n, s in mseg.items()}


def face_usage(ctx, obs, fit, min_gain: float = 0.1) -> dict[str, list[str]]:
    """Parameters each face carries: those whose variance grows by more than *min_gain*
    (or that become undetermined) when the face is left out of the normal matrix."""
    from hydrosync_core.methods.pool_calibration.joint import _system

    theta = np.array([*georef.boresight_angles(fit.r_m), *fit.lever])
    free = np.array([n not in fit.fixed for n in NAMES])
    if not free.any():
        return {}
    parts = {}
    for name, ob in obs.items():
        _, jac, _ = _system(ctx, {name: ob}, fit.r_m, fit.lever, theta[:3])
        jf = jac[:, free]
        parts[name] = jf.T @ jf
    total = sum(parts.values())
    base = np.diag(np.linalg.pinv(total))
    out = {}
    for name, part in parts.items():
        rest = total - part
        w = np.linalg.eigvalsh(rest)
        singular = w[0] <= w[-1] * 1e-12
        var = np.full(len(base), np.inf) if singular else np.diag(np.linalg.inv(rest))
        names = [n for n, f in zip(NAMES, free, strict=True) if f]
        out[name] = [n for n, v, b in zip(names, var, base, strict=True)
                     if not np.isfinite(v) or v > (1 + min_gain) * b]
    return out


def _sigmas(joint: JointSolution | None) -> dict[str, float]:
    """Parameter -> 1σ (° / m) of a joint solution."""
    if joint is None:
        return {}
    return {**joint.sigma_boresight_deg,
            **{f"lever_{k}": v for k, v in joint.sigma_lever_arm_m.items()}}


def contradictions(final_deg: dict, final_m: dict, coarse: dict, p: PoolParams,
                   held: set[str], usage: dict[str, list[str]],
                   sigma: dict[str, float] | None = None) -> dict[str, str]:
    """Parameters whose correction exceeds the stated coarse accuracy -> message.

    The coarse accuracy (``coarse_tol_deg``/``coarse_tol_m``) is a half-width the user vouches
    for; a correction beyond it by more than 3σ of the estimate (*sigma*: parameter -> σ in
    ° / m) means the data contradict the setup (a wrong sign or axis in the drawing, a
    mis-paired face, a target moved since it was surveyed), so it is flagged with the faces
    that carry the parameter and is not a calibration. Within 3σ of the bound the data
    cannot tell, and a true error right at the stated accuracy is not a contradiction.
    """
    b, la = coarse["boresight_deg"], coarse["lever_arm_m"]
    out = {}
    for name in NAMES:
        if name in held:
            continue
        if name.startswith("lever_"):
            k = name[-1]
            corr, tol, unit = final_m[k] - la[k], p.coarse_tol_m, " m"
        else:
            corr = (final_deg[name] - b[name] + 180.0) % 360.0 - 180.0
            tol, unit = p.coarse_tol_deg, "°"
        s = (sigma or {}).get(name)
        if abs(corr) > tol + 3.0 * (s if s is not None and np.isfinite(s) else 0.0):
            faces = sorted(f for f, used in usage.items() if name in used)
            out[name] = (f"correction {corr:+.3g}{unit} exceeds the coarse accuracy "
                         f"±{tol:g}{unit}: the data contradict the setup (faces carrying it: "
                         f"{', '.join(faces) or 'none'}); not a calibration — check the "
                         "setup, the target design and the face pairing")
    return out


def _seed(seg, p, mfaces, refs, progress, cancel) -> tuple[SeedSolution, list[dict], int,
                                                               dict[str, str], list[str]]:
    """Patent steps 3 then 4, alternated from the coarse values.

    The angles are first found with the coarse lever arm, whose error (through the varying
    attitude) slightly bends small faces, so the angle iteration is repeated with the
    corrected lever arm until both settle. Returns the seed solution, its iteration table,
    the number of rounds, the undetermined parameters (-> reason) and warnings.
    """
    mp, warnings = p.min_points, []
    lever, r_m, table, total_it = seg.lever0.copy(), seg.r_m0.copy(), [], 0
    for rnd in range(1, p.max_rounds + 1):
        check_cancel(cancel)
        angles = iterate_angles(seg.ctx, mfaces, seg.roles, refs, r_m,
                                lever, tol_deg=p.tol_deg, max_iter=p.max_iter,
                                min_points=mp,
                                progress=sub_progress(progress, (rnd - 1) / p.max_rounds,
                                                      rnd / p.max_rounds),
                                cancel=cancel)
        table += [dict(row, iteration=total_it + row["iteration"], round=rnd)
                  for row in angles.table]
        total_it += angles.iterations
        lev = lever_offsets(seg.ctx, mfaces, seg.roles, seg.design, refs,
                            seg.laser_points, angles.r_m, lever, min_points=mp)
        d_angle = np.degrees(np.linalg.norm(
            georef.boresight_angles(angles.r_m.T @ r_m)))
        d_lever = float(np.linalg.norm(lev.lever - lever))
        r_m, lever = angles.r_m, lev.lever
        if rnd > 1 and d_lever < p.lever_tol_m and d_angle < 10 * p.tol_deg:
            break
    converged = bool(angles.converged and d_lever < p.lever_tol_m)
    if not converged:
        warnings.append(f"seed method did not converge (last round: angle iteration "
                        f"{'converged' if angles.converged else 'not converged'}, lever-arm "
                        f"change {d_lever * 1000:.2f} mm)")
    reasons = {name: f"no {'/'.join(PARAMETER_ROLES[name])} face with a reference "
                     "plane seen by the multibeam" for name in angles.undetermined}
    reasons.update(lev.reasons or {})
    for name, why in reasons.items():
        warnings.append(f"seed method: {name} cannot be determined ({why}); kept at the "
                        "coarse value")
    seed = SeedSolution(_angles(r_m), _lever(lever), total_it, converged,
                        [float(v) for v in lev.shift_xyz_m], list(reasons))
    return seed, table, rnd, reasons, warnings


#: The final selection is redone around the joint solution while the solution moves any
#: selected sounding by more than RESELECT_SHIFT × the re-crop tolerance, at most
#: RESELECT_ROUNDS times.
RESELECT_SHIFT = 0.1
RESELECT_ROUNDS = 3


def _largest_shift(ctx, obs, setup_a, setup_b, sample: int = 4000) -> float:
    """Largest displacement (m) of the observed soundings (an evenly spread subset of at most
    *sample*) between two setups (boresight matrix, lever m)."""
    idx = np.concatenate([i for i, _ in obs.values()]) if obs else np.arange(0)
    if not len(idx):
        return 0.0
    idx = idx[::max(1, len(idx) // sample)]
    a = georef.georeference(ctx, *setup_a, select=idx)
    b = georef.georeference(ctx, *setup_b, select=idx)
    return float(np.max(np.linalg.norm(a - b, axis=1)))


def _joint(seg, p, mfaces, r_a, l_a, cancel):
    """Joint adjustment from the aligned setup (independent of the seed's outcome), held
    parameters at their coarse values; the points are re-selected around its own first
    solution, and again around the final one while it moves them (RESELECT_SHIFT).
    Returns (fit or None, observations, face indices, warnings)."""
    theta_c = np.array([*georef.boresight_angles(seg.r_m0), *seg.lever0])
    c_sig = (np.deg2rad(p.coarse_tol_deg) / np.sqrt(3), p.coarse_tol_m / np.sqrt(3))
    b_sig = (p.build_tol_m / np.sqrt(3), np.deg2rad(p.build_tol_deg) / np.sqrt(3))
    ins_sig = tuple(float(v) for v in np.deg2rad(p.ins_sigma_deg))
    kw = dict(huber_m=p.huber_m, cancel=cancel, block_s=p.sigma_block_s,
              ins_sigma_rad=ins_sig, ins_tau_s=p.ins_tau_s, refs=seg.refs,
              build_sigma=b_sig, coarse=theta_c, coarse_sigma=c_sig)
    obs = {}
    try:
        obs = _joint_obs(seg, mfaces, p.min_soundings)
        first = adjust(seg.ctx, obs, r_a, l_a, fix=structural_fix(seg.roles, obs),
                       covariance=False, huber_m=p.huber_m, cancel=cancel)
        mfaces = _resegment(seg, p, first.r_m, first.lever, cancel)
        obs = _joint_obs(seg, mfaces, p.min_soundings)
        # No structural hold here: without a horizontal face the vessel's roll and pitch
        # still tie lever z to the wall and the obliques; the data decide (singular normal
        # matrix, or σ not below the coarse accuracy). Holding it at a coarse value off by
        # up to the coarse accuracy biased the angles correlated with it (#24: single passes
        # without a visible top 2-20× worse than a plain point-to-plane fit).
        fit = adjust(seg.ctx, obs, first.r_m, first.lever, fix={}, **kw)
        r_sel, l_sel = first.r_m, first.lever
        for _ in range(RESELECT_ROUNDS):
            if _largest_shift(seg.ctx, obs, (r_sel, l_sel), (fit.r_m, fit.lever)) \
                    < RESELECT_SHIFT * p.refine_tol_m:
                break
            # The points were selected around a setup the solution has left (the first fit
            # holds lever z when no top is seen, and its coarse value may be 15 cm off): a
            # wall's foot then takes floor soundings, which tilt it (#24: roll at -3σ).
            r_sel, l_sel = fit.r_m, fit.lever
            mfaces = _resegment(seg, p, r_sel, l_sel, cancel)
            obs = _joint_obs(seg, mfaces, p.min_soundings)
            fit = adjust(seg.ctx, obs, r_sel, l_sel, fix={}, **kw)
    except (ValueError, np.linalg.LinAlgError) as exc:
        return None, obs, mfaces, [f"joint adjustment failed ({exc}); the seed solution is "
                                   "reported"]
    return fit, obs, mfaces, []


def _joint_solution(fit, p) -> tuple[JointSolution, dict[str, str], list[str]]:
    """The joint fit in user units, its flagged parameters (-> message) and warnings."""
    corr = correlation(fit.covariance)
    sig = np.sqrt(np.diag(fit.covariance))
    budget = _budget(fit)
    flagged = _flags(fit.covariance, fit.fixed, p, budget)
    joint = JointSolution(
        _angles(fit.r_m), _lever(fit.lever),
        dict(zip(("roll", "pitch", "yaw"), map(float, np.degrees(sig[:3])), strict=True)),
        _lever(sig[3:]), list(NAMES), corr.tolist(), fit.sigma0_m, fit.n_obs,
        fit.iterations, fit.converged, list(fit.fixed), fit.residual_rms,
        dict(zip(NAMES, map(float, fit.variance_factor), strict=True)),
        dict(fit.undetermined), budget)
    return joint, flagged, _corr_warnings(corr, p)


def _face_rows(seg, mfaces, obs, usage, r_final, l_final) -> list[FaceRow]:
    """One row per design face: points, plane fits, reference plane and what it carries."""
    final_pts = georef.georeference(seg.ctx, r_final, l_final)
    rows = []
    for name, role in seg.roles.items():
        lp = seg.laser_planes.get(name)
        ref = seg.refs.get(name)
        idx = mfaces.get(name, np.arange(0))
        mpl = fit_plane(final_pts[idx], role.normal) if len(idx) >= 3 else None
        rows.append(FaceRow(
            name, role.role, role.water, int(lp.n) if lp else 0, int(len(idx)),
            float(lp.rms) if lp else float("nan"), float(mpl.rms) if mpl else float("nan"),
            angle_deg(ref.plane.normal, mpl.normal) if ref and mpl else float("nan"),
            ",".join(usage.get(name, [])) if name in obs else "",
            ("own" if ref.kind == "own" else ref.source) if ref else "",
            tuple(float(v) for v in ref.translation) if ref else (float("nan"),) * 3,
            seg.pairing.get(name, "")))
    return rows


def pass_table(ctx, mfaces: dict[str, np.ndarray], refs) -> list[dict]:
    """Pings, soundings and soundings on referenced faces of each pass (see PoolResult)."""
    starts = ctx.pass_start if ctx.pass_start is not None else np.array([0])
    bounds = np.append(starts, len(ctx.origin))
    of_ping = np.searchsorted(bounds, ctx.ping, side="right") - 1
    used = np.zeros(len(ctx.ping), bool)
    for name, idx in mfaces.items():
        if name in refs:
            used[idx] = True
    return [{"pass": k + 1, "pings": int(bounds[k + 1] - bounds[k]),
             "soundings": int(np.sum(of_ping == k)),
             "on_faces": int(np.sum(used & (of_ping == k)))} for k in range(len(starts))]


def solve(seg, params: PoolParams | None = None, progress=None, cancel=None) -> PoolResult:
    """Run steps 3 and 4 of the patent and the joint adjustment on a segmentation.

    *params* default to those the segmentation was made with (the GUI may change the
    solving parameters between Segment and Iterate).
    """
    p = seg.params if params is None else params
    warnings = list(seg.warnings)
    refs = {n: r.plane for n, r in seg.refs.items()}
    r_a = seg.r_align if seg.r_align is not None else seg.r_m0
    l_a = seg.lever_align if seg.lever_align is not None else seg.lever0
    report(progress, 0.0, "selecting the multibeam face points around the aligned setup")
    mfaces = _resegment(seg, p, r_a, l_a, cancel)
    seed, table, rounds, seed_reasons, seed_warn = _seed(
        seg, p, mfaces, refs, sub_progress(progress, 0.0, 0.4), cancel)
    warnings += seed_warn
    report(progress, 0.5, "joint adjustment")
    fit, obs, mfaces, joint_warn = _joint(seg, p, mfaces, r_a, l_a, cancel)
    warnings += joint_warn
    joint, flagged, usage = None, {}, {}
    r_final, l_final, method = _matrix(seed.boresight_deg), _vector(seed.lever_arm_m), "seed"
    undetermined = dict(seed_reasons)
    if fit is not None:
        joint, flagged, corr_warn = _joint_solution(fit, p)
        warnings += corr_warn
        usage = face_usage(seg.ctx, obs, fit)
        if p.final == "joint" and fit.converged:
            r_final, l_final, method = fit.r_m, fit.lever, "joint"
            undetermined = dict(fit.undetermined)
    for name, why in (undetermined.items() if method == "joint" else ()):
        warnings.append(f"joint adjustment: {name} cannot be determined ({why}); kept at "
                        "the coarse value")
    contradicted = (contradictions(_angles(r_final), _lever(l_final), seg.coarse, p,
                                   set(undetermined), usage, _sigmas(joint))
                    if method == "joint" else {})
    for name, why in contradicted.items():
        flagged[name] = why + (f"; {flagged[name]}" if name in flagged else "")
    for name, why in flagged.items():
        warnings.append(f"joint adjustment: {name} {why}")
    report(progress, 0.9, "face table")
    rows = _face_rows(seg, mfaces, obs, usage, r_final, l_final)
    converged = bool(seed.converged and (joint is None or joint.converged))
    message = (f"seed: {seed.iterations} angle iterations in {rounds} rounds "
               f"({'converged' if seed.converged else 'not converged'}); final = {method}")
    if undetermined:
        message += f"; undetermined: {', '.join(undetermined)}"
    report(progress, 1.0, "pool calibration done")
    return PoolResult(_angles(r_final), _lever(l_final), seed.iterations, converged, message,
                      method, seg.coarse, seed, joint, rows, table, warnings,
                      seg.ctx.dropped_pings, seg.ctx.dropped_soundings, undetermined,
                      flagged, {"translation_m": p.build_tol_m,
                                "rotation_deg": p.build_tol_deg}, contradicted,
                      pass_table(seg.ctx, mfaces, seg.refs))
