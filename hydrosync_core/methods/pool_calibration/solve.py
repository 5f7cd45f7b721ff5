"""The solving half of the pool calibration: seed angles, seed lever arm, joint LSQ.

Runs on a :class:`~.api.Segmentation` (inputs as documented in :mod:`.api`); the result
is a :class:`~.result.PoolResult`.
"""

from __future__ import annotations

import numpy as np

from hydrosync_core.methods.pool_calibration import georef
from hydrosync_core.methods.pool_calibration.joint import NAMES, adjust, correlation
from hydrosync_core.methods.pool_calibration.lever_arm import lever_offsets
from hydrosync_core.methods.pool_calibration.params import PoolParams
from hydrosync_core.methods.pool_calibration.planes import PlaneFit, angle_deg, fit_plane
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


def _height_offset(seg, laser_pts_ok) -> tuple[float, float] | None:
    """As-built height offset (m) of the above-water horizontal faces: mean laser height
    minus design height, point-weighted, and its variance; None without such a face."""
    above = [n for n, r in seg.roles.items() if r.role == "horizontal" and r.water == "above"
             and n in laser_pts_ok]
    if not above:
        return None
    dz = np.concatenate([laser_pts_ok[n][:, 2] - seg.design[n].centroid[2] for n in above])
    return float(dz.mean()), float(dz.var() / len(dz))


def _joint_obs(seg, mfaces, min_points):
    """Reference plane per face: its laser plane, or for a below-water horizontal face the
    design plane raised by the as-built height offset measured on the laser tops."""
    obs = {}
    off = _height_offset(seg, {n: seg.laser_points[n] for n in seg.laser_planes})
    for name, idx in mfaces.items():
        if len(idx) < min_points:
            continue
        role = seg.roles[name]
        below_h = role.role == "horizontal" and role.water == "below"
        if name in seg.laser_planes and not below_h:
            obs[name] = (idx, seg.laser_planes[name])
        elif below_h and off is not None:
            d = seg.design[name]
            n = role.normal
            # Design height difference (step 4.2): horizontal plane z = z_design + offset.
            c = d.centroid + np.array([0.0, 0.0, off[0]])
            axes = np.column_stack([n, np.cross(n, [1.0, 0, 0]), np.cross(n, [0, 1.0, 0])])
            obs[name] = (idx, PlaneFit(n, float(n @ c), c, 0.0, len(idx), 0.0, axes, None,
                                       np.diag([0.0, 0.0, off[1]])))
    return obs


def _joint_warnings(cov, corr, fixed, p) -> list[str]:
    out = []
    sig = np.sqrt(np.clip(np.diag(cov), 0, None))
    for k, name in enumerate(NAMES):
        if name in fixed:
            out.append(f"joint adjustment: {name} cannot be determined from this pass "
                       "geometry (kept at the seed value)")
            continue
        s, lim, unit = (np.degrees(sig[k]), p.max_sigma_deg, "°") if k < 3 else \
            (sig[k], p.max_sigma_m, " m")
        if s > lim:
            out.append(f"joint adjustment: {name} poorly determined (σ = {s:.4g}{unit} > "
                       f"{lim}{unit})")
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
                         band_sigma=p.refine_band_sigma, cancel=cancel)
    return {n: s.indices for n, s in mseg.items()}


def solve(seg, params: PoolParams | None = None, progress=None, cancel=None) -> PoolResult:
    """Run steps 3 and 4 of the patent and the joint adjustment on a segmentation.

    *params* default to those the segmentation was made with (the GUI may change the
    solving parameters between Segment and Iterate).
    """
    p = seg.params if params is None else params
    warnings = list(seg.warnings)
    mp = p.min_points
    # Seed steps 3 then 4, alternated: the angles are first found with the coarse lever
    # arm, whose error (through the varying attitude) slightly bends small faces, so the
    # angle iteration is repeated with the corrected lever arm until both settle.
    lever, r_m, table, total_it = seg.lever0.copy(), seg.r_m0.copy(), [], 0
    mfaces = seg.mbes_faces
    for rnd in range(1, p.max_rounds + 1):
        check_cancel(cancel)
        if rnd == 2:
            # Coarse-setup crops are wide; re-crop tightly around the first solution (once,
            # so that later rounds work on a fixed point set and can converge).
            mfaces = _resegment(seg, p, r_m, lever, cancel)
        angles = iterate_angles(seg.ctx, mfaces, seg.roles, seg.laser_planes, r_m,
                                lever, tol_deg=p.tol_deg, max_iter=p.max_iter,
                                min_points=mp,
                                progress=sub_progress(progress, 0.4 * (rnd - 1) / p.max_rounds,
                                                      0.4 * rnd / p.max_rounds),
                                cancel=cancel)
        table += [dict(row, iteration=total_it + row["iteration"], round=rnd)
                  for row in angles.table]
        total_it += angles.iterations
        lev = lever_offsets(seg.ctx, mfaces, seg.roles, seg.design, seg.laser_planes,
                            seg.laser_points, angles.r_m, lever, min_points=mp)
        d_angle = np.degrees(np.linalg.norm(
            georef.boresight_angles(angles.r_m.T @ r_m)))
        d_lever = float(np.linalg.norm(lev.lever - lever))
        r_m, lever = angles.r_m, lev.lever
        if rnd > 1 and d_lever < p.lever_tol_m and d_angle < 10 * p.tol_deg:
            break
    seed_converged = bool(angles.converged and d_lever < p.lever_tol_m)
    if not seed_converged:
        warnings.append(f"seed method did not converge (last round: angle iteration "
                        f"{'converged' if angles.converged else 'not converged'}, lever-arm "
                        f"change {d_lever * 1000:.2f} mm)")
    for name in angles.undetermined:
        warnings.append(f"seed method: {name} cannot be determined (no "
                        f"{'/'.join(PARAMETER_ROLES[name])} face seen by both sensors); "
                        "kept at the coarse value")
    for name in lev.undetermined:
        warnings.append(f"seed method: {name} cannot be determined; kept at the coarse value")
    seed = SeedSolution(_angles(r_m), _lever(lever), total_it, seed_converged,
                        [float(v) for v in lev.shift_xyz_m],
                        list(angles.undetermined + lev.undetermined))
    report(progress, 0.5, "re-segmenting the multibeam cloud with the seed solution")
    mfaces = _resegment(seg, p, r_m, lever, cancel)
    obs = _joint_obs(seg, mfaces, mp)
    joint, r_final, l_final, method = None, r_m, lever, "seed"
    try:
        # Without a horizontal face the vertical offset rests only on the vessel's roll
        # and pitch motion: fixed rather than reported as a weak, possibly wrong number.
        has_h = any(seg.roles[n].role == "horizontal" for n in obs)
        fit = adjust(seg.ctx, obs, r_m, lever, huber_m=p.huber_m, cancel=cancel,
                     fix=() if has_h else ("lever_z",),
                     block_s=p.sigma_block_s,
                     ins_sigma_rad=tuple(np.deg2rad(p.ins_sigma_deg)),
                     ins_tau_s=p.ins_tau_s)
    except (ValueError, np.linalg.LinAlgError) as exc:
        warnings.append(f"joint adjustment failed ({exc}); the seed solution is reported")
        fit = None
    if fit is not None:
        corr = correlation(fit.covariance)
        sig = np.sqrt(np.clip(np.diag(fit.covariance), 0, None))
        warnings += _joint_warnings(fit.covariance, corr, fit.fixed, p)
        joint = JointSolution(
            _angles(fit.r_m), _lever(fit.lever),
            dict(zip(("roll", "pitch", "yaw"), map(float, np.degrees(sig[:3])), strict=True)),
            _lever(sig[3:]), list(NAMES), corr.tolist(), fit.sigma0_m, fit.n_obs,
            fit.iterations, fit.converged, list(fit.fixed), fit.residual_rms,
            dict(zip(NAMES, map(float, fit.variance_factor), strict=True)))
        if p.final == "joint" and fit.converged:
            r_final, l_final, method = fit.r_m, fit.lever, "joint"
    report(progress, 0.9, "face table")
    final_pts = georef.georeference(seg.ctx, r_final, l_final)
    rows = []
    used = {n: [k for k, roles in PARAMETER_ROLES.items() if seg.roles[n].role in roles]
            for n in seg.design}
    for name, role in seg.roles.items():
        lp = seg.laser_planes.get(name)
        idx = mfaces.get(name, np.arange(0))
        mpl = fit_plane(final_pts[idx], role.normal) if len(idx) >= 3 else None
        rows.append(FaceRow(
            name, role.role, role.water, int(lp.n) if lp else 0, int(len(idx)),
            float(lp.rms) if lp else float("nan"), float(mpl.rms) if mpl else float("nan"),
            angle_deg(lp.normal, mpl.normal) if lp and mpl else float("nan"),
            ",".join(used[name]) if name in obs else ""))
    converged = bool(seed_converged and (joint is None or joint.converged))
    message = (f"seed: {total_it} angle iterations in {rnd} rounds "
               f"({'converged' if seed_converged else 'not converged'}); final = {method}")
    report(progress, 1.0, "pool calibration done")
    return PoolResult(_angles(r_final), _lever(l_final), total_it, converged, message,
                      method, seg.coarse, seed, joint, rows, table, warnings,
                      seg.ctx.dropped_pings, seg.ctx.dropped_soundings)
