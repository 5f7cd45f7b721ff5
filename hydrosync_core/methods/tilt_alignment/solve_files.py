"""Solve a tilt-pole data set held as columns (from the CSV files or a project).

Shared by the command's file form and the project form: GNSS columns (ENU or geodetic)
to the local NED frame, :func:`.pipeline.solve_record`, and the ``result.json`` document
of ``docs/formats.md``.
"""

from __future__ import annotations

import math

import numpy as np

from hydrosync_core.errors import InputError
from hydrosync_core.methods.tilt_alignment.io import (
    check_imu_times,
    gnss_to_local,
    local_to_output,
    ned_std_to_enu,
    normal_gravity,
)
from hydrosync_core.methods.tilt_alignment.params import TiltParams
from hydrosync_core.methods.tilt_alignment.pipeline import TiltSolution, solve_record

IMU_KEYS = ("time", "gx", "gy", "gz", "ax", "ay", "az")


def solve_columns(imu: dict, gnss: dict, length: float, params: TiltParams,
                  sources=("imu.csv", "gnss.csv"), progress=None, cancel=None,
                  imu_convention: str | None = None) -> tuple[TiltSolution, dict]:
    """Solve from IMU and GNSS columns; returns the solution and the GNSS frame.

    *imu_convention*: what the data set declares (``pole.json``); the option wins."""
    for key in IMU_KEYS:
        if key not in imu:
            raise InputError(sources[0], "missing column", field=key)
    time = np.asarray(imu["time"], float)
    check_imu_times(time, sources[0])
    gyro = np.column_stack([imu[k] for k in ("gx", "gy", "gz")]).astype(float)
    accel = np.column_stack([imu[k] for k in ("ax", "ay", "az")]).astype(float)
    if not ("e" in gnss or "lat" in gnss):
        raise InputError(sources[1], "needs e, n, u or lat, lon, height", field="e")
    ned, frame = gnss_to_local(gnss)
    gt = np.asarray(gnss["time"], float)
    g = params.gravity_m_s2
    if g is None and frame["form"] == "llh":
        g = normal_gravity(frame["origin_llh"][0], frame["origin_llh"][2])
    try:
        sol = solve_record(time, gyro, accel, gt, ned, length, params, gravity=g,
                           progress=progress, cancel=cancel, imu_convention=imu_convention)
    except InputError as exc:
        raise InputError(sources[1], exc.message, field=exc.field) from None
    return sol, frame


def result_document(sol: TiltSolution, frame: dict, length: float, params: TiltParams
                    ) -> dict:
    """The ``result.json`` document (see ``docs/formats.md`` and the module of the CLI)."""
    key = "tip_enu" if frame["form"] == "enu" else "tip_llh"
    methods = {}
    for name, m in sol.methods.items():
        methods[name] = {
            key: local_to_output(m.tip, frame) if m.ok else None,
            "tip_std_enu_m": ned_std_to_enu(m.tip_std) if m.ok else None,
            "heading_misalignment_deg": math.degrees(m.psi) if m.ok else None,
            "heading_std_deg": math.degrees(m.psi_std) if m.ok else None,
            "iterations": m.iterations, "converged": m.converged, "vectors": m.vectors,
            "undetermined": m.undetermined, "warning": m.warning}
    chosen = sol.methods[params.method]
    undetermined = [] if chosen.ok else [f"{params.method}: {chosen.undetermined}"]
    doc = {
        key: methods[params.method][key],
        "tip_std_enu_m": methods[params.method]["tip_std_enu_m"],
        "heading_misalignment_deg": methods[params.method]["heading_misalignment_deg"],
        "heading_std_deg": methods[params.method]["heading_std_deg"],
        "method": params.method,
        "vectors_used": sol.vectors.n_used if sol.screening is None else 0,
        "vectors_rejected": sol.vectors.n_rejected if sol.screening is None
        else int(sol.vectors.used.size),
        "vectors_short": sol.vectors.short,
        "screening": sol.screening,
        "pole_length_m": length,
        "gnss_epochs": int(sol.gnss_time.size),
        "tilt_deg": {"max": math.degrees(float(np.max(sol.epoch_tilt))),
                     "shot": math.degrees(float(np.mean(sol.epoch_tilt[sol.tip_window])))},
        "gravity_m_s2": sol.gravity,
        "imu_grade": params.imu_grade,
        "imu_convention": sol.imu_convention,
        "priors": {"gyro_bias_deg_s": params.gyro_bias_prior_deg_s,
                   "accel_bias_m_s2": params.accel_bias_prior_m_s2},
        "methods": methods,
        "undetermined": undetermined,
        "warnings": sol.warnings,
        "params": params.to_dict(),
    }
    if sol.joint is not None:
        j = sol.joint
        doc["joint"] = {"gyro_bias_deg_s": np.degrees(j.gyro_bias).tolist(),
                        "accel_bias_m_s2": j.accel_bias.tolist(),
                        "sigma_gnss_m": j.sigma_gnss_m, "rms_gnss_m": j.rms_gnss_m,
                        "sigma_gnss_v_m": j.sigma_gnss_v_m,
                        "sigma_dv_m_s": j.sigma_dv_m_s, "accel_blocks": j.n_blocks,
                        "gyro_noise_deg_s_per_sample": math.degrees(j.gyro_noise_rad_s),
                        "accel_noise_m_s2_per_sample": j.accel_noise_m_s2,
                        "iterations": j.iterations, "converged": j.converged,
                        "weak_azimuth_deg": math.degrees(math.atan2(
                            j.weak_direction[1], j.weak_direction[0])) % 180.0,
                        "weak_std_m": j.weak_sigma_m, "weak_bias_share": j.bias_share,
                        "time_offset_ms": 1000 * (j.time_offset_applied_s + j.time_offset_s),
                        "time_offset_std_ms": 1000 * j.time_offset_std_s,
                        "time_offset_applied_ms": 1000 * j.time_offset_applied_s}
    if frame["form"] == "llh":
        doc["origin_llh"] = frame["origin_llh"]
    return doc
