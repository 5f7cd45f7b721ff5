"""Run the GNSS/INS smoother on a project and store the results (plugin entry point).

Inputs read from the project (``hydrosync import P.h5 --gins-imu … --gins-gnss …
--gins-config … [--gins-reference …]``):

* ``raw/gins/imu``: ``time`` (s), ``dtheta_x/y/z`` (rad), ``dvel_x/y/z`` (m/s), body FRD;
* ``raw/gins/gnss``: ``time``, ``lat``, ``lon`` (deg), ``height`` (m), ``sd_n/e/d`` (m),
  antenna;
* ``raw/gins/config``: the KF-GINS configuration keys (JSON);
* ``raw/gins/reference`` (optional): a reference trajectory (``.nav`` columns) for the
  error statistics; ``raw/gins/outages`` (optional JSON ``{"windows": [[start, end], …]}``)
  GNSS outages to simulate.

Stored layout — ``/results/gins_smoother``: attributes ``json`` (the parameters),
``params_schema_version``, ``software_version``, ``run_utc``, ``counts``, ``alignment``,
``gnss_model`` (the noise model used and what its σ were computed from),
``evaluation`` (JSON, :func:`.evaluate.evaluate` or ``{}``), ``outages`` (JSON windows);
tables ``forward`` and ``smoothed`` (``time``, ``lat``, ``lon``, ``height``, ``vn``,
``ve``, ``vd``, ``roll``, ``pitch``, ``yaw`` and ``sd_*`` of each; degrees, m, m/s),
``imu_errors`` (per node, forward and smoothed biases), ``gnss`` (innovations and
residuals, NED m).
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from pathlib import Path

import numpy as np

from hydrosync_core.errors import InputError
from hydrosync_core.jsonsafe import jsonable
from hydrosync_core.methods.gins_smoother import VERSION
from hydrosync_core.methods.gins_smoother.params import GinsParams
from hydrosync_core.progress import check_cancel, report, sub_progress
from hydrosync_core.provenance import record

RESULT = "results/gins_smoother"
RAW = "raw/gins"
IMU, GNSS, CONFIG, REFERENCE, OUTAGES = (f"{RAW}/imu", f"{RAW}/gnss", f"{RAW}/config",
                                         f"{RAW}/reference", f"{RAW}/outages")
IMU_COLS = ("dtheta_x", "dtheta_y", "dtheta_z", "dvel_x", "dvel_y", "dvel_z")
MAX_STORED_ROWS = 2_000_000
#: A GNSS−IMU clock offset beyond this is a unit mistake (ms given as s), not a latency.
MAX_CLOCK_OFFSET_S = 10.0


# ----------------------------------------------------------------- import readers
def imu_table(path) -> dict:
    """``hydrosync import --gins-imu``: KF-GINS IMU text or ``imu.csv`` → columns."""
    from hydrosync_core.methods.gins_smoother.io import read_imu

    d = read_imu(path)
    out = {"time": d.time}
    out.update({c: d.inc[:, i] for i, c in enumerate(IMU_COLS)})
    return out


def gnss_table(path) -> dict:
    """``hydrosync import --gins-gnss``: KF-GINS GNSS text or ``gnss.csv`` → columns."""
    from hydrosync_core.methods.gins_smoother.io import read_gnss

    d = read_gnss(path)
    return {"time": d.time, "lat": d.llh[:, 0], "lon": d.llh[:, 1], "height": d.llh[:, 2],
            "sd_n": d.std[:, 0], "sd_e": d.std[:, 1], "sd_d": d.std[:, 2]}


def nav_table(path) -> dict:
    """``hydrosync import --gins-reference``: an 11-column ``.nav`` → columns."""
    from hydrosync_core.methods.gins_smoother.io import read_nav

    return nav_columns(read_nav(path))


def config_json(path) -> dict:
    """``hydrosync import --gins-config``: KF-GINS YAML (or JSON) → checked keys."""
    from hydrosync_core.methods.gins_smoother.config import read_config

    return read_config(path).to_dict()


def store_recording(project, target: str, path, clock_offset: float | None = None,
                    **_options) -> str:
    """``hydrosync import --gins-recording FOLDER [--clock-offset S]``: a real recording
    folder (comma2k19 segment or rtklibexplorer drive/walk, :mod:`.recordings`) →
    ``raw/gins/imu``, ``gnss``, ``config`` and, when the recording has one, ``reference``.

    The GNSS-minus-IMU clock offset *clock_offset* (s, the GNSS epoch tagged t happened at
    IMU time t + S) is applied when given; otherwise it is estimated from the turns
    (:func:`.recordings.estimate_time_shift`, no filter pass). It, its σ (NaN when given)
    and the recording's notes are stored as attributes of ``raw/gins``, so every later run
    uses it without being told again.
    """
    import math

    from hydrosync_core.methods.gins_smoother.recordings import (
        estimate_time_shift,
        read_recording,
        shifted,
    )

    rec = read_recording(path)
    if clock_offset is not None:
        shift = float(clock_offset)
        if not math.isfinite(shift) or abs(shift) > MAX_CLOCK_OFFSET_S:
            raise InputError(str(path), f"clock offset {clock_offset!r} s: expected a finite "
                             f"number within ±{MAX_CLOCK_OFFSET_S:g} s",
                             field="--clock-offset")
        est = None
        clock = f"GNSS−IMU clock offset {shift:+.3f} s given"
    else:
        shift, est = estimate_time_shift(rec)
        clock = est.text() if est is not None else "the recording's own timing"
    rec = shifted(rec, shift)
    imu = {"time": rec.imu.time}
    imu.update({c: rec.imu.inc[:, i] for i, c in enumerate(IMU_COLS)})
    g = rec.gnss
    for sub in ("imu", "gnss", "config", "reference", "outages"):
        if project.exists(f"{target}/{sub}"):
            project.delete(f"{target}/{sub}")
    project.put_table(f"{target}/imu", imu, source=str(path), units="rad, m/s, body FRD")
    project.put_table(f"{target}/gnss", {"time": g.time, "lat": g.llh[:, 0],
                                         "lon": g.llh[:, 1], "height": g.llh[:, 2],
                                         "sd_n": g.std[:, 0], "sd_e": g.std[:, 1],
                                         "sd_d": g.std[:, 2]}, source=str(path))
    project.put_json(f"{target}/config", rec.config.to_dict())
    if rec.reference is not None:
        project.put_table(f"{target}/reference", nav_columns(rec.reference), source=str(path))
    project.set_attrs(target, recording=rec.name, time_shift_s=shift, time_shift=clock,
                      time_shift_sigma_s=est.sigma_s if est is not None else float("nan"),
                      notes=json.dumps(rec.notes), recommended_params=json.dumps(rec.params))
    return (f"{Path(path).name} -> /{target}: {rec.name}, {rec.imu.time.size} IMU epochs "
            f"({rec.imu.rate_hz:.0f} Hz), {g.time.size} GNSS fixes"
            + (", reference" if rec.reference is not None else "")
            + f"; {clock}, applied")


def nav_columns(nav) -> dict:
    return {"time": nav.time, "lat": nav.llh[:, 0], "lon": nav.llh[:, 1],
            "height": nav.llh[:, 2], "vn": nav.vel[:, 0], "ve": nav.vel[:, 1],
            "vd": nav.vel[:, 2], "roll": nav.att[:, 0], "pitch": nav.att[:, 1],
            "yaw": nav.att[:, 2]}


def trajectory_columns(tr) -> dict:
    """The stored columns of a :class:`.filter.Trajectory`."""
    out = {"time": tr.time, "lat": tr.llh[:, 0], "lon": tr.llh[:, 1], "height": tr.llh[:, 2],
           "vn": tr.vel[:, 0], "ve": tr.vel[:, 1], "vd": tr.vel[:, 2], "roll": tr.att[:, 0],
           "pitch": tr.att[:, 1], "yaw": tr.att[:, 2]}
    for i, k in enumerate(("n", "e", "d")):
        out[f"sd_{k}"] = tr.pos_std[:, i]
        out[f"sd_v{k}"] = tr.vel_std[:, i]
    for i, k in enumerate(("roll", "pitch", "yaw")):
        out[f"sd_{k}"] = tr.att_std[:, i]
    return out


def table_trajectory(tab):
    """A :class:`.filter.Trajectory` from a stored ``forward``/``smoothed`` table."""
    from hydrosync_core.methods.gins_smoother.filter import Trajectory

    def cols(*names):
        return np.column_stack([np.asarray(tab[n], float) for n in names])

    return Trajectory(np.asarray(tab["time"], float), cols("lat", "lon", "height"),
                      cols("vn", "ve", "vd"), cols("roll", "pitch", "yaw"),
                      cols("sd_n", "sd_e", "sd_d"), cols("sd_vn", "sd_ve", "sd_vd"),
                      cols("sd_roll", "sd_pitch", "sd_yaw"))


def load_reference(project):
    """The stored reference trajectory (:class:`.io.NavData`) or None."""
    from hydrosync_core.methods.gins_smoother.io import NavData

    if not project.exists(REFERENCE):
        return None
    r = project.get_table(REFERENCE)
    return NavData(np.asarray(r["time"], float),
                   np.column_stack([r["lat"], r["lon"], r["height"]]),
                   np.column_stack([r["vn"], r["ve"], r["vd"]]),
                   np.column_stack([r["roll"], r["pitch"], r["yaw"]]), f"/{REFERENCE}")


def stored_errors(project) -> dict:
    """Per-epoch errors (with the solution's σ) of the stored forward and smoothed
    trajectories against the stored reference: ``{name: error_series}``; empty without a
    reference or results."""
    from hydrosync_core.methods.gins_smoother.evaluate import error_series

    ref = load_reference(project)
    out = {}
    if ref is None:
        return out
    for name in ("forward", "smoothed"):
        if project.exists(f"{RESULT}/{name}"):
            e = error_series(table_trajectory(project.get_table(f"{RESULT}/{name}")), ref)
            if e["time"].size:
                out[name] = e
    return out


# ----------------------------------------------------------------- run
def load_inputs(project):
    """IMU, GNSS, sensor configuration, reference (or None) and outage windows."""
    from hydrosync_core.methods.gins_smoother.config import config_from_dict
    from hydrosync_core.methods.gins_smoother.io import GnssData, ImuData, NavData

    for path in (IMU, GNSS, CONFIG):
        if not project.exists(path):
            raise InputError(f"/{path}", "missing (import --gins-imu, --gins-gnss and "
                             "--gins-config)")
    it = project.get_table(IMU)
    gt = project.get_table(GNSS)
    for tab, cols, path in ((it, ("time",) + IMU_COLS, IMU),
                            (gt, ("time", "lat", "lon", "height", "sd_n", "sd_e", "sd_d"),
                             GNSS)):
        for c in cols:
            if c not in tab:
                raise InputError(f"/{path}", "column missing", field=c)
            if not np.all(np.isfinite(tab[c])):
                raise InputError(f"/{path}", "non-finite values", field=c)
    imu = ImuData(np.asarray(it["time"], float),
                  np.column_stack([np.asarray(it[c], float) for c in IMU_COLS]), f"/{IMU}")
    gnss = GnssData(np.asarray(gt["time"], float),
                    np.column_stack([gt["lat"], gt["lon"], gt["height"]]).astype(float),
                    np.column_stack([gt["sd_n"], gt["sd_e"], gt["sd_d"]]).astype(float),
                    f"/{GNSS}")
    cfg = config_from_dict(project.get_json(CONFIG, {}), f"/{CONFIG}")
    ref = None
    if project.exists(REFERENCE):
        r = project.get_table(REFERENCE)
        ref = NavData(np.asarray(r["time"], float),
                      np.column_stack([r["lat"], r["lon"], r["height"]]),
                      np.column_stack([r["vn"], r["ve"], r["vd"]]),
                      np.column_stack([r["roll"], r["pitch"], r["yaw"]]), f"/{REFERENCE}")
    windows = []
    if project.exists(OUTAGES):
        doc = project.get_json(OUTAGES, {})
        try:
            windows = [(float(a), float(b)) for a, b in doc.get("windows", [])]
        except (TypeError, ValueError):
            raise InputError(f"/{OUTAGES}", "expected [[start, end], …]",
                             field="windows") from None
    return imu, gnss, cfg, ref, windows


def run(project, params: GinsParams | Mapping | None = None, progress=None, cancel=None):
    """Forward filter and smoother on the project's data; replace ``/results/gins_smoother``.

    Returns the :class:`.filter.GinsResult`. Raises :class:`InputError` for missing or
    bad inputs and :class:`Cancelled` when cancelled (nothing stored then).
    """
    from hydrosync_core.methods.gins_smoother.evaluate import evaluate
    from hydrosync_core.methods.gins_smoother.filter import run_gins

    if isinstance(params, GinsParams):
        p = params
    else:  # a recording imported with --gins-recording brings its recommended options
        base = {}
        if project.exists(RAW):
            try:
                base = json.loads(project.attrs(RAW).get("recommended_params", "{}"))
            except (TypeError, ValueError):
                base = {}
        p = GinsParams.from_dict({**base, **dict(params or {})})
    check_cancel(cancel)
    imu, gnss, cfg, ref, windows = load_inputs(project)
    report(progress, 0.02, "inputs read")
    res = run_gins(imu, gnss.without(windows) if windows else gnss, cfg, p,
                   sub_progress(progress, 0.02, 0.9), cancel)
    check_cancel(cancel)
    ev = evaluate(res, ref, windows) if ref is not None else {}
    check_cancel(cancel)
    report(progress, 0.93, "storing")
    project.delete(RESULT)
    project.put_json(RESULT, p.to_dict())
    project.set_attrs(RESULT, counts=json.dumps(res.counts), alignment=json.dumps(res.alignment),
                      gnss_model=json.dumps(jsonable(res.gnss_model)),
                      evaluation=json.dumps(ev), outages=json.dumps(windows))
    project.put_table(f"{RESULT}/forward", trajectory_columns(res.forward), units="deg, m")
    if res.smoothed is not None:
        project.put_table(f"{RESULT}/smoothed", trajectory_columns(res.smoothed),
                          units="deg, m")
    errs = {"time": res.imu_errors_forward["time"]}
    for name, d in (("fwd", res.imu_errors_forward), ("smo", res.imu_errors_smoothed)):
        if d is None:
            continue
        for k, v in d.items():
            if k != "time":
                for i, a in enumerate("xyz"):
                    errs[f"{name}_{k}_{a}"] = v[:, i]
    project.put_table(f"{RESULT}/imu_errors", errs)
    g = {"time": res.gnss["time"], "used": res.gnss["used"]}
    for key in ("innovation", "residual", "residual_forward"):
        if key in res.gnss:
            for i, a in enumerate("ned"):
                g[f"{key}_{a}"] = res.gnss[key][:, i]
    project.put_table(f"{RESULT}/gnss", g, units="m")
    inputs = [IMU, GNSS, CONFIG] + [x for x in (REFERENCE, OUTAGES) if project.exists(x)]
    record(project, RESULT, inputs, p, plugin_version=VERSION)
    report(progress, 1.0, "GNSS/INS trajectory stored")
    return res
