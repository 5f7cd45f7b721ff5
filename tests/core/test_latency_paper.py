"""``estimator = qi2010`` is the published method exactly (issue #29 item 4): the same lines
and the same Δt as an independent, plain-numpy implementation of Qi et al. (2010).

The reference below shares no code with HydroSync's estimator: its own epoch selection
(the documented rule: tags in [start + skip, end] whose shifted times stay inside the
attitude record over the scan range widened by the refinement margin), ``np.polyfit``
detrending (eq. 1), the total heave from the rotation written out (eq. 2),
``np.interp`` of the whole record (eq. 3), ``np.corrcoef`` (eq. 4), the grid argmax,
then the documented sub-step refinement (R on a fine grid of SUBDIVISIONS + 1 points over
±1 step, the vertex of the parabola through the best fine point and its neighbours), the
paper's rule R_max > 0.85 and the R-weighted mean. One rule is HydroSync's in both: a
line whose grid maximum lies on the scan's edge has no peak inside the range and is not
used (the paper presumes a range that holds the delay; keeping it would print the edge
with σ = 0).

Power: 6 simulated 1 Hz days (paper and coloured noise, calm to rough sea, 8 lines, some
with R_max below the threshold), i.e. ~50 line decisions and per-line Δt: a screening rule
beyond the paper (edge, σ credibility, outliers) or a different refinement changes a
line's decision or its Δt by far more than the 0.01 ms tolerance (the grid step is 5 ms).
"""

from __future__ import annotations

import numpy as np
import pytest

from hydrosync_core.methods.latency import estimate_latency
from hydrosync_core.methods.latency.simulate import scenario, simulate_day

STEP_S, RANGE_S, MIN_R = 0.005, (-1.0, 1.0), 0.85
MARGIN_S = 0.15  # documented attitude margin beyond the scan range (lines.MARGIN_S)
SUBDIVISIONS = 40  # documented refinement grid (correlation.SUBDIVISIONS)


def _total_heave(att: dict, arm) -> np.ndarray:
    """Seed eq. 2 written out: H_T = heave − [(R·L)_z − L_z], R = Rz·Ry(pitch)·Rx(roll)."""
    x, y, z = arm
    r, p = np.radians(att["roll"]), np.radians(att["pitch"])
    rz = -np.sin(p) * x + np.cos(p) * np.sin(r) * y + np.cos(p) * np.cos(r) * z
    return att["heave"] - (rz - z)


def _r(tags, h, t_att, h_att, dts) -> np.ndarray:
    return np.array([np.corrcoef(h, np.interp(tags - dt, t_att, h_att))[0, 1] for dt in dts])


def _paper(day: dict, arm, skip_s: float = 0.0) -> tuple[list, list, float]:
    """Per line (Δt, R_max) or None, the used mask and the R-weighted mean."""
    g, att, lines = day["gnss"], day["attitude"], day["lines"]
    t_att, h_att = att["time"], _total_heave(att, arm)
    dts = np.linspace(RANGE_S[0], RANGE_S[1], int(round((RANGE_S[1] - RANGE_S[0]) / STEP_S)) + 1)
    lo, hi = RANGE_S[0] - MARGIN_S, RANGE_S[1] + MARGIN_S
    peaks = []
    for start, end in zip(lines["start"], lines["end"], strict=True):
        t = g["time"]
        sel = ((t >= start + skip_s) & (t <= end) & (t - hi >= t_att[0])
               & (t - lo <= t_att[-1]))
        tags, hgt = t[sel], g["height"][sel]
        if tags.size < 30:
            peaks.append(None)
            continue
        h = hgt - np.polyval(np.polyfit(tags - tags.mean(), hgt, 1), tags - tags.mean())
        curve = _r(tags, h, t_att, h_att, dts)
        k = int(np.argmax(curve))
        if 0 < k < dts.size - 1:
            fine = np.linspace(dts[k - 1], dts[k + 1], SUBDIVISIONS + 1)
            rf = _r(tags, h, t_att, h_att, fine)
            j = int(np.argmax(rf))
            a, b, c = rf[j - 1:j + 2] if 0 < j < fine.size - 1 else (0.0, 0.0, 0.0)
            denom = a - 2 * b + c
            if 0 < j < fine.size - 1 and denom < 0:
                shift = 0.5 * (a - c) / denom
                peaks.append((fine[j] + shift * (fine[1] - fine[0]),
                              max(b - 0.25 * (a - c) * shift, b)))
            else:
                peaks.append((fine[j], rf[j]))
        else:
            peaks.append((dts[k], curve[k]))
    # A grid maximum on the scan's edge is no peak (the paper assumes the range holds the
    # delay): such a line is not used (HydroSync says so in a warning).
    edge = [pk is not None and pk[0] in (dts[0], dts[-1]) for pk in peaks]
    used = [pk is not None and pk[1] > MIN_R and not e
            for pk, e in zip(peaks, edge, strict=True)]
    w = np.array([pk[1] for pk, u in zip(peaks, used, strict=True) if u])
    x = np.array([pk[0] for pk, u in zip(peaks, used, strict=True) if u])
    return peaks, used, float(np.sum(w * x) / np.sum(w)) if w.size else float("nan")


DAYS = [("paper", "calm", 1), ("paper", "rough", 2), ("coloured", "moderate", 3),
        ("coloured", "rough", 4), ("coloured", "calm", 5), ("paper", "moderate", 6)]


@pytest.mark.parametrize(("noise", "sea", "seed"), DAYS)
def test_qi2010_equals_an_independent_implementation_of_the_paper(noise, sea, seed):
    rng = np.random.default_rng(seed)
    cfg = scenario(noise, sea, n_lines=8, line_s=120.0, turn_s=20.0, run_in_s=5.0,
                   gnss_hz=1.0, attitude_hz=20.0, latency_s=float(rng.uniform(-0.4, 0.4)))
    day = simulate_day(cfg, seed=seed)
    peaks, used, mean = _paper(day, cfg.lever_arm_m)
    res = estimate_latency(day["gnss"], day["attitude"], day["lines"], cfg.lever_arm_m,
                           {"estimator": "qi2010", "step_s": STEP_S})
    assert [ln.used for ln in res.lines] == used
    for ln, pk in zip(res.lines, peaks, strict=True):
        if pk is not None:
            assert ln.latency_s == pytest.approx(pk[0], abs=1e-5), ln.name
            assert ln.r_max == pytest.approx(pk[1], abs=1e-9), ln.name
    assert res.latency_s == pytest.approx(mean, abs=1e-5, nan_ok=True)
    assert "paper's line rule" in res.message


def test_extended_screening_is_an_option_of_qi2010():
    """The further rules stay available to qi2010 (screening = extended) and remain the
    default of the other estimators."""
    from hydrosync_core.methods.latency.params import LatencyParams

    assert LatencyParams(estimator="qi2010").paper_screening()
    assert not LatencyParams(estimator="qi2010", screening="extended").paper_screening()
    assert not LatencyParams(estimator="weighted").paper_screening()
    assert LatencyParams(estimator="weighted", screening="paper").paper_screening()
