"""Latency v2 speed paths: exact closed-form scan, line slices, fast CSV reading.

Each fast path is checked against the straightforward evaluation it replaces.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from hydrosync_core.errors import InputError
from hydrosync_core.importers import fastcsv as shared_fastcsv
from hydrosync_core.importers import survey_csv
from hydrosync_core.methods.latency import fastscan, passes, readers, weighted
from hydrosync_core.methods.latency.correlation import (
    correlation_curve,
    correlation_curve_direct,
)
from hydrosync_core.methods.latency.estimate import estimate_latency
from hydrosync_core.methods.latency.heave import total_heave, total_heave_at, total_heave_deg
from hydrosync_core.methods.latency.heave_windows import HeaveWindows
from hydrosync_core.methods.latency.inputs import set_up
from hydrosync_core.methods.latency.lines import attitude_window, line_epochs, line_slice
from hydrosync_core.methods.latency.simulate import DayConfig, simulate_day, write_day_csv

DAY = DayConfig(n_lines=3, line_s=60.0, turn_s=10.0, run_in_s=5.0, gnss_hz=10.0,
                attitude_hz=50.0)


@pytest.fixture(scope="module")
def day():
    return simulate_day(DAY, seed=4)


def test_fast_scan_equals_direct_interpolation_on_irregular_data():
    rng = np.random.default_rng(0)
    # Jittered attitude (logger time tags) and jittered GNSS tags, a grid that starts and
    # ends outside the attitude record (np.interp holds the end values there).
    t_att = np.cumsum(rng.uniform(0.005, 0.015, 3000))
    h_att = np.sin(t_att * 1.3) + 0.1 * rng.standard_normal(t_att.size)
    tags = np.sort(rng.uniform(0.5, 29.5, 200))
    h = np.sin(tags * 1.3 - 0.4) + 0.05 * rng.standard_normal(tags.size)
    for dts in (np.linspace(-1, 1, 2001), np.linspace(-0.6, 0.7, 27), np.linspace(0.1, 0.1002, 41),
                np.linspace(-3, 3, 61)):
        fast = correlation_curve(tags, h, t_att, h_att, dts)
        direct = correlation_curve_direct(tags, h, t_att, h_att, dts)
        np.testing.assert_allclose(fast, direct, rtol=0, atol=1e-10)
    # A non-uniform grid takes the direct path.
    dts = np.array([-0.3, -0.1, 0.0, 0.4])
    np.testing.assert_array_equal(correlation_curve(tags, h, t_att, h_att, dts),
                                  correlation_curve_direct(tags, h, t_att, h_att, dts))
    assert fastscan.uniform_step(dts) is None and fastscan.available()


def test_lattice_scan_equals_direct_interpolation_on_regular_attitude():
    rng = np.random.default_rng(1)
    # Regular attitude (the lattice kernel), jittered GNSS tags; the steps divide the
    # attitude interval 1, 2, 10 and 200 times; the last two grids do not fit the lattice
    # (7.5 steps per sample; candidates beyond the record) and take the general kernel.
    t_att = 1000.0 + np.arange(3000) * 0.01
    h_att = np.sin(t_att * 1.3) + 0.1 * rng.standard_normal(t_att.size)
    tags = np.sort(rng.uniform(1002.0, 1027.0, 300))
    h = np.sin(tags * 1.3 - 0.4) + 0.05 * rng.standard_normal(tags.size)
    grids = [(np.linspace(-1, 1, 201), True), (np.linspace(-1, 1, 401), True),
             (np.linspace(-1, 1, 2001), True), (np.linspace(0.1, 0.1002, 5), True),
             (np.linspace(-1, 1, 1501), False), (np.linspace(-3, 3, 6001), False)]
    for dts, lattice in grids:
        step = fastscan.uniform_step(dts)
        assert (fastscan._lattice(tags, t_att, dts, step) is not None) == lattice
        fast = correlation_curve(tags, h, t_att, h_att, dts)
        direct = correlation_curve_direct(tags, h, t_att, h_att, dts)
        np.testing.assert_allclose(fast, direct, rtol=0, atol=1e-10)
        sums = fastscan.correlation_sums(tags, h, t_att, h_att, dts, step)
        general = fastscan._sums(tags, h, t_att, h_att, dts, step)
        np.testing.assert_allclose(sums, general, rtol=1e-11, atol=1e-9)


def test_lattice_kernel_row_loops_equal_the_single_loop_bit_for_bit():
    """The vectorisable per-row loops (long lag ranges) and the single fused loop (short
    ones) perform the same operations per element: the same sums to the last bit."""
    rng = np.random.default_rng(7)
    t_att = 1000.0 + np.arange(12000) * 0.01
    h_att = np.sin(t_att * 1.3) + 0.1 * rng.standard_normal(t_att.size)
    tags = np.sort(rng.uniform(1005.0, 1115.0, 1100))
    w = rng.standard_normal(tags.size)
    for dts in (np.linspace(-1, 1, 2001), np.linspace(-1, 1, 401), np.linspace(0.1, 0.1002, 41),
                np.linspace(0.02, 0.22, 21), np.linspace(-0.5, 0.5, 1001), np.array([0.3, 0.301])):
        step = fastscan.uniform_step(dts)
        x, L = fastscan._lattice(tags, t_att, dts, step)
        split = fastscan._lattice_sums(x, w, h_att, L, dts.size, 0)
        fused = fastscan._lattice_sums(x, w, h_att, L, dts.size, 10**9)
        for a, b in zip(split, fused, strict=True):
            np.testing.assert_array_equal(a, b)
        np.testing.assert_array_equal(
            fastscan.correlation_sums(tags, w, t_att, h_att, dts, step)[0], split[0])
    # Regular tags on the regular attitude: the epochs in one residue (or two: rounding puts
    # a position just below its integer), the others skipped.
    tags = 1010.0 + np.arange(1000) * 0.1
    h = np.sin(tags * 1.3 - 0.4) + 0.05 * rng.standard_normal(tags.size)
    for dts in (np.linspace(-1, 1, 2001), np.linspace(0.1, 0.1002, 41)):
        step = fastscan.uniform_step(dts)
        x, L = fastscan._lattice(tags, t_att, dts, step)
        assert np.unique(np.floor(x).astype(int) % L).size <= 2
        np.testing.assert_allclose(correlation_curve(tags, h, t_att, h_att, dts),
                                   correlation_curve_direct(tags, h, t_att, h_att, dts),
                                   rtol=0, atol=1e-10)


def test_fast_scan_constant_heave_is_nan():
    tags = np.linspace(1, 9, 50)
    r = correlation_curve(tags, np.sin(tags), np.linspace(0, 10, 500), np.full(500, 0.3),
                          np.linspace(-0.5, 0.5, 11))
    assert np.all(np.isnan(r))


def test_line_slice_matches_mask(day):
    t_g, t_att = day["gnss"]["time"], day["attitude"]["time"]
    for start, end in zip(day["lines"]["start"], day["lines"]["end"], strict=True):
        for skip, lo, hi in ((0.0, -1.15, 1.15), (7.0, 0.3, 0.3), (0.0, -5.0, 0.0)):
            mask = (t_g >= start + skip) & (t_g <= end)
            mask &= (t_g - hi >= t_att[0]) & (t_g - lo <= t_att[-1])
            sl = line_slice(t_g, start, end, skip, t_att, lo, hi)
            np.testing.assert_array_equal(np.flatnonzero(mask), np.arange(t_g.size)[sl])
            np.testing.assert_array_equal(line_epochs(t_g, start, end, skip, t_att, lo, hi), mask)
    assert line_slice(t_g, t_att[-1] + 10, t_att[-1] + 20, 0.0, t_att, -1, 1) == slice(0, 0)


def test_compiled_total_heave_equals_numpy():
    rng = np.random.default_rng(2)
    for n in (1000, 250_000):  # serial and parallel kernels
        heave, roll, pitch = rng.normal(size=n), rng.normal(size=n) * 5, rng.normal(size=n) * 2
        np.testing.assert_allclose(
            total_heave_deg(heave, roll, pitch, (-1.5, 2.0, -6.0)),
            total_heave(heave, np.radians(roll), np.radians(pitch), (-1.5, 2.0, -6.0)),
            rtol=0, atol=1e-13)


def test_estimate_equals_the_straightforward_method(day, monkeypatch):
    """The whole estimate with the closed-form scan equals the pre-v2 direct scan."""
    params = {"step_s": 0.002}
    fast = estimate_latency(day["gnss"], day["attitude"], day["lines"], DAY.lever_arm_m,
                                params)
    monkeypatch.setattr(fastscan, "available", lambda: False)
    slow = estimate_latency(day["gnss"], day["attitude"], day["lines"], DAY.lever_arm_m,
                                params)
    assert fast.latency_s == pytest.approx(slow.latency_s, abs=1e-7)
    for a, b in zip(fast.lines, slow.lines, strict=True):
        assert a.latency_s == pytest.approx(b.latency_s, abs=1e-7)
        assert a.r_max == pytest.approx(b.r_max, abs=1e-9)
        assert a.uncertainty_s == pytest.approx(b.uncertainty_s, rel=1e-6)
        assert a.sigma0_after_m == pytest.approx(b.sigma0_after_m, abs=1e-12)
    np.testing.assert_allclose(fast.r_curves, slow.r_curves, atol=1e-9)


def test_fast_csv_reads_what_the_generic_reader_reads(day, tmp_path):
    write_day_csv(day, tmp_path)
    for name in ("gnss", "attitude"):
        fast = getattr(readers, f"read_{name}_csv")(tmp_path / f"{name}.csv")
        slow = getattr(survey_csv, f"read_{name}_csv")(tmp_path / f"{name}.csv")
        assert list(fast) == list(slow)
        for key in slow:
            np.testing.assert_array_equal(fast[key], slow[key])
    down = readers.read_attitude_csv(tmp_path / "attitude.csv", "down", ("time", "heave"))
    assert list(down) == ["time", "heave"]
    np.testing.assert_array_equal(down["heave"], -slow["heave"])


def test_fast_csv_small_pieces_and_optional_columns(tmp_path, monkeypatch):
    monkeypatch.setattr(shared_fastcsv, "PIECE_BYTES", 64)  # many pieces, rows cut at piece ends
    path = tmp_path / "gnss.csv"
    rows = "".join(f"{100 + i * 0.1:.1f},{42 + 0.001 * i:.3f},7,x,{i % 5}\r\n"
                   for i in range(300))
    path.write_text("Time,height,extra,note,quality\r\n" + rows + "\r\n", newline="")
    fast = readers.read_gnss_csv(path)
    slow = survey_csv.read_gnss_csv(path)
    assert list(fast) == list(slow) == ["time", "height", "quality"]
    for key in slow:
        np.testing.assert_array_equal(fast[key], slow[key])


@pytest.mark.parametrize("newline, last", [("\n", "\n"), ("\r\n", ""), ("\n", "")])
def test_compiled_csv_parser_returns_the_generic_readers_doubles(tmp_path, monkeypatch,
                                                                 newline, last):
    monkeypatch.setattr(shared_fastcsv, "COMPILED_CHUNK", 97)  # many chunks, cut inside rows
    rng = np.random.default_rng(8)
    n = 2000
    cols = [345600 + np.cumsum(rng.uniform(0.001, 0.02, n)), rng.normal(0, 5, n),
            rng.normal(0, 2, n), rng.uniform(0, 360, n), rng.normal(0, 0.5, n)]
    fmts = ["{:.4f}", "{:.6f}", "{:.15f}", "{:.3f}", "{:.9f}"]
    text = "\n".join(",".join(f.format(c[i]) for f, c in zip(fmts, cols, strict=True))
                     for i in range(n))
    text = text.replace("-0.000000000,", "-0.000000000,") + "\n"
    path = tmp_path / "attitude.csv"
    path.write_bytes(("time,roll,pitch,heading,heave\n" + text).replace(
        "\n", newline).encode()[: -len(newline)] + last.encode())
    names, header = shared_fastcsv._header(path)
    keep = ["time", "roll", "pitch", "heave"]
    from hydrosync_core import plausible
    compiled = shared_fastcsv._read_compiled(path, names, header, names, keep,
                                             plausible.ATTITUDE, 2)
    assert compiled is not None  # the compiled parser took this file
    slow = survey_csv.read_attitude_csv(path)
    for key in keep:
        np.testing.assert_array_equal(compiled[key], slow[key])
    fast = readers.read_attitude_csv(path)
    assert list(fast) == list(slow)
    for key in slow:
        np.testing.assert_array_equal(fast[key], slow[key])


@pytest.mark.parametrize("body", [
    "time,height\n1,42.0\n2,4.2e1\n3,42.1\n",                  # exponent
    "time,height\n1,42.0\n2,42.12345678901234567\n3,42.1\n",   # more than 15 digits
    "time,height\n1,42.0\n\n2,42.1\n",                         # blank line
    "time,height\n1,42.0\n2, 42.1\n",                           # space
    "time,height\n1,42.0\n2,+42.1\n",                           # plus sign
])
def test_compiled_csv_parser_leaves_other_shapes_to_the_general_readers(tmp_path, body):
    path = tmp_path / "gnss.csv"
    path.write_text(body)
    names, header = shared_fastcsv._header(path)
    from hydrosync_core import plausible
    assert shared_fastcsv._read_compiled(path, names, header, ["time", "height"],
                                  ["time", "height"], plausible.GNSS, 2) is None
    fast, slow = readers.read_gnss_csv(path), survey_csv.read_gnss_csv(path)
    for key in slow:
        np.testing.assert_array_equal(fast[key], slow[key])


@pytest.mark.parametrize("body, where", [
    ("time,height\n1,42.0\n2,abc\n3,42.1\n", ":3"),           # not a number
    ("time,height\n1,42.0\n2,nan\n3,42.1\n", ":3"),           # not finite
    ("time,height\n1,42.0\n2,42.1,7\n3,42.1\n", ":3"),        # extra field
    ("time,height\n1,42.0\n1,42.1\n3,42.1\n", ":3"),          # duplicate time
    ("time,height\n1,42.0\n2,1e9\n3,42.1\n", ":3"),           # implausible height
    ("time,hgt\n1,42.0\n2,42.1\n", ":1"),                     # missing column
])
def test_fast_csv_bad_files_give_the_generic_error(tmp_path, body, where):
    path = tmp_path / "gnss.csv"
    path.write_text(body)
    with pytest.raises(InputError) as slow:
        survey_csv.read_gnss_csv(path)
    with pytest.raises(InputError) as fast:
        readers.read_gnss_csv(path)
    assert fast.value.one_line() == slow.value.one_line()
    assert where in fast.value.one_line()


def test_fast_csv_unsorted_and_commented_files_match(tmp_path):
    path = tmp_path / "gnss.csv"
    path.write_text("# logger export\ntime,height\n3,42.3\n1,42.1\n2,42.2\n")
    fast, slow = readers.read_gnss_csv(path), survey_csv.read_gnss_csv(path)
    np.testing.assert_array_equal(fast["time"], [1, 2, 3])
    np.testing.assert_array_equal(fast["height"], slow["height"])


def test_cli_on_quiet_day_is_unchanged(tmp_path):
    """The quiet test day gives the same numbers through the CLI's fast readers."""
    cfg = replace(DAY, latency_s=0.21)
    d = simulate_day(cfg, seed=9)
    write_day_csv(d, tmp_path)
    g = readers.read_gnss_csv(tmp_path / "gnss.csv")
    a = readers.read_attitude_csv(tmp_path / "attitude.csv", "up", ("time", "roll", "pitch",
                                                                    "heave"))
    res = estimate_latency(g, a, survey_csv.read_lines_csv(tmp_path / "lines.csv"),
                               cfg.lever_arm_m)
    ref = estimate_latency(survey_csv.read_gnss_csv(tmp_path / "gnss.csv"),
                               survey_csv.read_attitude_csv(tmp_path / "attitude.csv"),
                               survey_csv.read_lines_csv(tmp_path / "lines.csv"),
                               cfg.lever_arm_m)
    assert res.latency_s == ref.latency_s and res.to_dict() == ref.to_dict()


def test_total_heave_at_times_equals_whole_record_interpolation(day):
    att = day["attitude"]
    source = HeaveWindows(att, np.asarray(DAY.lever_arm_m))
    full = total_heave_deg(att["heave"], att["roll"], att["pitch"], DAY.lever_arm_m)
    rng = np.random.default_rng(5)
    times = np.concatenate([rng.uniform(att["time"][0] - 1, att["time"][-1] + 1, 500),
                            att["time"][[0, 7, -1]]])
    np.testing.assert_array_equal(source.at(times), np.interp(times, att["time"], full))


def test_total_heave_at_equals_interpolated_total_heave():
    rng = np.random.default_rng(3)
    t = np.cumsum(rng.uniform(0.005, 0.015, 5000))
    heave, roll, pitch = rng.normal(size=5000), rng.normal(size=5000) * 5, rng.normal(size=5000) * 2
    # Sorted and unsorted times, times on the samples and beyond both ends, sorted times
    # further apart than the walk from one to the next goes (WALK_STEPS), repeated times.
    times = np.concatenate([np.sort(rng.uniform(t[0] - 1, t[-1] + 1, 3000)),
                            rng.uniform(t[0], t[-1], 500), t[:50],
                            np.sort(rng.uniform(t[0], t[-1], 30)), t[[7, 7, 7, 4000, 4999]]])
    arm = (-1.5, 2.0, -6.0)
    np.testing.assert_allclose(total_heave_at(times, t, heave, roll, pitch, arm),
                               np.interp(times, t, total_heave_deg(heave, roll, pitch, arm)),
                               rtol=0, atol=1e-13)


def test_pooled_weighting_gives_noise_only_frequencies_no_weight():
    from hydrosync_core.methods.latency import prefilter

    rng = np.random.default_rng(11)
    dt, pairs = 0.05, []
    for _ in range(13):  # 13 two-minute lines at 20 Hz: waves at 0.15 Hz plus white noise
        t = np.arange(2400) * dt
        wave = np.sin(2 * np.pi * 0.15 * t + rng.uniform(0, 6.3))
        pairs.append((wave + 0.05 * rng.standard_normal(t.size),
                      wave + 0.05 * rng.standard_normal(t.size)))
    w = prefilter.pooled_weighting(pairs, dt)
    noise = w.f > 1.0
    # Spurious coherence of the noise band (≈ 1/K per bin) no longer gets weight.
    assert np.mean(w.coherence[noise] == 0) > 0.99 and np.mean(w.gain[noise] == 0) > 0.99
    assert w.coherence[np.argmin(np.abs(w.f - 0.15))] > 0.9


def test_filter_steps_equal_fft_filter():
    """spectrum → response_gains → filtered is fft_filter; a spectrum cut to its first bins
    gives the same numbers for a response that is zero beyond them."""
    from hydrosync_core.methods.latency import prefilter

    rng = np.random.default_rng(8)
    f_w = np.fft.rfftfreq(640, 0.1)  # a weighting estimated at 10 Hz GNSS
    weighting = prefilter.Weighting(f_w, rng.uniform(0, 0.9, f_w.size),
                                    rng.uniform(0, 1, f_w.size), 5.0)
    for n in (3, 4, 17, 1000, 18231):
        x = np.cumsum(rng.standard_normal(n)) + 0.01 * np.arange(n)
        crop = slice(n // 5, n - n // 7)
        for response in (lambda f: prefilter.antialias_response(f, 4.0), weighting.response):
            ref = prefilter.fft_filter(x, 0.01, response)
            spec = prefilter.spectrum(x)
            gains = prefilter.response_gains(response, spec.size, 0.01)
            np.testing.assert_array_equal(prefilter.filtered(spec, gains, crop), ref[crop])
        keep = passes.band_bins(spec.size, 0.01, 0.1)
        head = spec.head(keep)
        assert n < 4 or head.bins.size == keep < spec.bins.size
        gains = prefilter.response_gains(weighting.response, spec.size, 0.01)
        assert head.covers(gains[0]) and head.covers(gains)  # the bins, and the support
        np.testing.assert_allclose(prefilter.filtered(head, gains, crop),
                                   prefilter.fft_filter(x, 0.01, weighting.response)[crop],
                                   rtol=0, atol=1e-12)
    # The mirrored padding is np.pad(mode="symmetric")'s.
    for n in range(4, 60):
        x = rng.standard_normal(n)
        spec = prefilter.spectrum(x)
        d = x - (spec.intercept + spec.slope * (np.arange(n, dtype=float) - 0.5 * (n - 1)))
        np.testing.assert_array_equal(spec.bins, np.fft.rfft(np.pad(
            d, (spec.left, spec.size - n - spec.left), mode="symmetric")))
    spec = prefilter.spectrum(np.cumsum(rng.standard_normal(18231)))
    head = spec.head(passes.band_bins(spec.size, 0.01, 0.1))
    # A response beyond the kept bins is refused, not silently cut.
    gains = prefilter.response_gains(lambda f: prefilter.antialias_response(f, 4.0),
                                     spec.size, 0.01)
    assert not head.covers(gains[0]) and not head.covers(gains)
    assert gains.support == np.flatnonzero(gains.values)[-1] + 1
    with pytest.raises(ValueError):
        prefilter.filtered(head, gains)
    with pytest.raises(ValueError):  # a plain (gains, gain at 0 Hz) pair is checked too
        prefilter.filtered(head, (gains.values, gains.dc))


def test_first_pass_windows_equal_per_line_filtering():
    """The anti-aliased heave and the kept spectra of the first pass equal each line's
    padded window filtered on its own; the pooled pairs read from the scan window differ
    from those of a window filtered around Δt0 alone only by the filter's tail beyond the
    PAD_S padding (~1e-11 m on heave of ~0.1 m)."""
    from hydrosync_core.methods.latency import prefilter
    from hydrosync_core.methods.latency.correlation import heave_at
    from hydrosync_core.methods.latency.params import LatencyParams

    cfg = replace(DAY, n_lines=6, gnss_hz=5.0)  # 6 Welch segments: prefilter.MIN_SEGMENTS
    d = simulate_day(cfg, seed=12)
    p = LatencyParams.from_dict({"estimator": "weighted"})
    setup = set_up(d["gnss"], d["attitude"], d["lines"], cfg.lever_arm_m, p)
    scans = passes.first_passes(setup, p, False, True, None, None, aa_sigma=False, keep=True)
    setup.prepared, peaks, works = scans.aa_lines, scans.aa_peaks, scans.works
    att, arm, t = setup.att, np.asarray(cfg.lever_arm_m), setup.att["time"]
    pad = int(round(prefilter.PAD_S / setup.a_int))
    cutoff = prefilter.ANTIALIAS_FRACTION * 0.5 / setup.g_int
    weighting = weighted.pooled_weighting(setup.prepared, peaks, works, t, p.min_r, setup.g_int)
    assert weighting is not None
    dt0 = float(np.median([pk.latency_s for pk in peaks]))
    lo, hi = float(setup.dts[0]), float(setup.dts[-1])

    def filtered_window(tags, a, b, response):  # the per-line filtering this replaces
        inner = attitude_window(t, tags, a, b)
        win = slice(max(inner.start - pad, 0), min(inner.stop + pad, t.size))
        h = total_heave_deg(att["heave"][win], att["roll"][win], att["pitch"][win], arm)
        crop = slice(inner.start - win.start, inner.stop - win.start)
        return t[inner], prefilter.fft_filter(h, setup.a_int, response)[crop]

    for line, work in zip(setup.prepared, works, strict=True):
        ta, ha = filtered_window(line.tags, lo, hi,
                                 lambda f: prefilter.antialias_response(f, cutoff))
        np.testing.assert_array_equal(t[work.inner], ta)
        np.testing.assert_array_equal(work.antialiased, ha)
        _, hw = filtered_window(line.tags, lo, hi, weighting.response)
        gains = prefilter.response_gains(weighting.response, work.spectrum.size, setup.a_int)
        crop = slice(work.inner.start - work.padded.start, work.inner.stop - work.padded.start)
        np.testing.assert_allclose(prefilter.filtered(work.spectrum, gains, crop), hw,
                                   rtol=0, atol=1e-12)
        ta0, ha0 = filtered_window(line.tags, dt0, dt0,
                                   lambda f: prefilter.antialias_response(f, cutoff))
        np.testing.assert_allclose(heave_at(line.tags, np.array([dt0]), ta, ha),
                                   heave_at(line.tags, np.array([dt0]), ta0, ha0),
                                   rtol=0, atol=1e-10)


def test_next_fast_len_and_numpy_fft_match_scipy_fft():
    """The filter's FFT length and transforms are scipy.fft's (numpy.fft is the same
    pocketfft), without importing scipy.fft on the command line."""
    from scipy import fft

    from hydrosync_core.methods.latency import prefilter

    for n in [*range(1, 2000), 36401, 36450, 36865, 99991, 131073]:
        assert prefilter.next_fast_len(n) == fft.next_fast_len(n, real=True), n
    rng = np.random.default_rng(2)
    for size in (36864, 3600, 640):
        x = rng.standard_normal(size)
        spec = np.fft.rfft(x)
        np.testing.assert_allclose(spec, fft.rfft(x), rtol=0, atol=1e-12)
        np.testing.assert_allclose(np.fft.irfft(spec, size), fft.irfft(spec, size), rtol=0,
                                   atol=1e-12)


def test_compiled_scan_helpers_equal_numpy():
    """The compiled replacements of numpy steps in the scan give numpy's numbers."""
    from hydrosync_core.methods.latency import lines

    rng = np.random.default_rng(4)
    cases = [(0.1, 0.1002, 41), (-1.0, 1.0, 2001), (0.3 - 0.1, 0.3 + 0.1, 21), (2.5, 2.5, 7),
             (-3.7, 11.0, 2), *((rng.normal(), rng.normal(), int(rng.integers(2, 500)))
                                for _ in range(50))]
    for start, stop, num in cases:
        np.testing.assert_array_equal(fastscan.grid(start, stop, num),
                                      np.linspace(start, stop, num))

    def old_uniform_step(dts):
        if dts.size < 2:
            return None
        step = (float(dts[-1]) - float(dts[0])) / (dts.size - 1)
        if not step > 0:
            return None
        if np.max(np.abs(np.diff(dts) - step)) > 1e-9 * max(step, 1e-300):
            return None
        return step

    for dts in (np.linspace(-1, 1, 2001), np.array([0.0]), np.array([1.0, 0.0]),
                np.array([-0.3, -0.1, 0.0, 0.4]), np.array([0.0, np.nan, 2.0]),
                np.linspace(0, 1, 11) + np.r_[0, 1e-12, np.zeros(9)]):
        assert fastscan.uniform_step(dts) == old_uniform_step(dts)

    for curve in (rng.normal(size=50), np.r_[np.nan, 0.3, 0.7, np.nan, 0.7, -0.2],
                  np.full(5, np.nan), np.r_[np.nan, np.nan, -0.5], np.array([0.2]),
                  np.r_[np.nan, np.inf, 0.1, -np.inf], np.r_[np.inf, np.nan, -np.inf]):
        k, low = lines._argmax_min(curve)
        if np.any(np.isfinite(curve)):
            assert (k, low) == (int(np.nanargmax(curve)), float(np.nanmin(curve)))
        else:
            assert k == -1

    for jitter in (0.0, 1e-9, 1e-8, 2e-8, 1e-6):
        ta = 1000.0 + np.arange(5000) * 0.01 + jitter * rng.standard_normal(5000)
        interval = (ta[-1] - ta[0]) / (ta.size - 1)
        limit = fastscan.LATTICE_TOLERANCE * interval
        assert fastscan._departs_py(ta, interval, limit) == (
            fastscan._departure(ta, interval) > limit)
        assert fastscan._departs(ta, interval, limit) == (
            fastscan._departure(ta, interval) > limit)

    F, S1, S2 = rng.normal(size=(3, 300))
    S2 = np.abs(S2) * 50.0
    S2[:5], S1[:5] = 1.0, np.sqrt(1.0 * 40)  # constant heave: var = 0
    n, mean_w = 40, 0.013
    with np.errstate(invalid="ignore", divide="ignore"):
        var = S2 - S1 * S1 / n
        ref = (F - S1 * mean_w) / np.sqrt(var)
    ref[~(var > 1e-12 * np.abs(S2) + 1e-300)] = np.nan
    np.testing.assert_array_equal(fastscan.pearson(F, S1, S2, n, mean_w), ref)


def _python_scan(monkeypatch, line, ta, ha, dts, **kw):
    """scan_line by its Python steps (the compiled line scan switched off)."""
    from hydrosync_core.methods.latency import lines

    with monkeypatch.context() as m:
        m.setattr(fastscan, "scan_core", lambda *a, **k: None)
        return lines.scan_line(line, ta, ha, dts, **kw)


def test_compiled_line_scan_equals_the_python_steps(monkeypatch):
    """fastscan.scan_core (curve, maximum, refinement, σ in one compiled call) gives the
    Python steps' numbers, warnings and flags: regular and jittered attitude, grids on and
    off the lattice, a peak inside and at the edge, constant heave, refine/σ off."""
    from hydrosync_core.methods.latency.lines import LineData, scan_line

    rng = np.random.default_rng(11)
    checked = 0
    for case in range(24):
        rate = (50.0, 100.0, 200.0)[case % 3]
        t_att = 500.0 + np.arange(int(90 * rate)) / rate
        if case % 6 == 5:  # the record ends inside the scan: np.interp holds its end values
            t_att = t_att[int(9.6 * rate):int(80.5 * rate)]
        if case % 4 == 1:
            t_att = t_att + 2e-4 / rate * rng.standard_normal(t_att.size)  # logger jitter
        delay = rng.uniform(-0.4, 0.4)
        period = rng.uniform(4.0, 12.0)
        h_att = (np.sin(2 * np.pi * t_att / period) + 0.3 * np.sin(t_att * 0.9 + 1.0)
                 + 0.05 * rng.standard_normal(t_att.size))
        g_rate = (1.0, 5.0, 10.0, 20.0)[case % 4]
        tags = np.arange(510.0, 580.0, 1.0 / g_rate) + 0.003 * rng.standard_normal(
            int(70 * g_rate))
        h = (np.interp(tags - delay, t_att, h_att) + 0.02 * rng.standard_normal(tags.size))
        h -= h.mean()
        step = (0.001, 0.002, 0.0075, 0.02)[case % 4]
        lo = -1.0 if case != 7 else delay + 0.05  # case 7: the peak at the grid's edge
        dts = np.linspace(lo, lo + 2.0, int(round(2.0 / step)) + 1)
        for refine, unc in ((True, True), (True, False), (False, True), (False, False)):
            fast_line = LineData("L", 0.0, 1.0, tags, h)
            slow_line = LineData("L", 0.0, 1.0, tags, h)
            fast = scan_line(fast_line, t_att, h_att, dts, refine=refine, uncertainty=unc)
            slow = _python_scan(monkeypatch, slow_line, t_att, h_att, dts, refine=refine,
                                uncertainty=unc)
            np.testing.assert_allclose(fast.curve, slow.curve, rtol=0, atol=1e-12)
            assert fast.at_edge == slow.at_edge == (case == 7)
            assert fast.r_max == pytest.approx(slow.r_max, abs=1e-12)
            assert fast.latency_s == pytest.approx(slow.latency_s, abs=1e-10)
            if unc and not fast.at_edge:
                assert fast.uncertainty_s == pytest.approx(slow.uncertainty_s, rel=1e-9)
                assert np.isfinite(fast.uncertainty_s)
            else:
                assert np.isnan(fast.uncertainty_s) and np.isnan(slow.uncertainty_s)
            assert fast_line.warnings == slow_line.warnings
            checked += 1
    assert checked == 96
    # Constant heave: no maximum, the same warning.
    tags = np.arange(10.0, 60.0, 0.1)
    flat = [LineData("F", 0.0, 1.0, tags, np.sin(tags)) for _ in range(2)]
    t_att, h_att = np.arange(0.0, 80.0, 0.01), np.full(8000, 0.25)
    dts = np.linspace(-1.0, 1.0, 201)
    fast = scan_line(flat[0], t_att, h_att, dts)
    slow = _python_scan(monkeypatch, flat[1], t_att, h_att, dts)
    assert np.isnan(fast.r_max) and np.isnan(slow.r_max)
    assert flat[0].warnings == flat[1].warnings and "constant" in flat[0].warnings[0]
    # Where the compiled scan does not apply it says so (the caller takes the Python path).
    h = np.sin(tags)
    assert fastscan.scan_core(tags, h, t_att, np.sin(t_att), np.array([-0.3, 0.0, 0.4]),
                              True, True, 40, 0.15, 15.0, 0.05, 0.1) is None
    assert fastscan.scan_core(tags[:1], h[:1], t_att, np.sin(t_att), dts, True, True, 40,
                              0.15, 15.0, 0.05, 0.1) is None


def test_closed_form_detrend_equals_polyfit():
    from numpy.polynomial import polynomial as npoly

    from hydrosync_core.methods.latency.detrend import detrend

    rng = np.random.default_rng(12)
    for degree in (0, 1, 2):
        for n in (1, 2, 3, 50, 1200):
            t = 4.3e5 + np.sort(rng.uniform(0, 120, n))
            hgt = 41.0 + 0.002 * (t - t[0]) + 0.1 * rng.standard_normal(n)
            if n <= degree:
                continue
            res, coef = detrend(t, hgt, degree)
            tc = t - t.mean()
            scale = max(float(np.abs(tc).max()), 1e-9)
            ref = npoly.polyfit(tc / scale, hgt, degree)
            np.testing.assert_allclose(res, hgt - npoly.polyval(tc / scale, ref), rtol=0,
                                       atol=1e-12)
            np.testing.assert_allclose(coef, ref / scale ** np.arange(degree + 1), rtol=1e-9,
                                       atol=1e-12)


def test_pooled_spectra_equal_scipy_welch_per_line():
    """The lines' Welch spectra, transformed a block of lines at a time, are
    scipy.signal.welch/csd's (linear detrend, Hann, half overlap), weighted by each
    line's samples and summed; blocks split anywhere give the same sums."""
    from scipy import signal

    from hydrosync_core.methods.latency import prefilter

    rng = np.random.default_rng(13)
    fs, nper = 10.0, 64
    pairs = []
    for _ in range(7):
        n = int(rng.integers(nper, 700))
        x = np.cumsum(rng.standard_normal(n)) + 0.01 * np.arange(n)
        pairs.append((x, 0.7 * x + rng.standard_normal(n)))
    ref = [np.zeros(nper // 2 + 1), np.zeros(nper // 2 + 1), np.zeros(nper // 2 + 1, complex)]
    for x, y in pairs:
        kw = {"fs": fs, "nperseg": nper, "detrend": "linear"}
        _, pxx = signal.welch(x, **kw)
        _, pyy = signal.welch(y, **kw)
        f_ref, pxy = signal.csd(x, y, **kw)
        for k, p in enumerate((pxx, pyy, pxy)):
            ref[k] = ref[k] + x.size * p
    out = prefilter._pooled_spectra(pairs, fs, nper)
    np.testing.assert_allclose(out[0], f_ref)
    for got, want in zip(out[1:], ref, strict=True):
        np.testing.assert_allclose(got, want, rtol=1e-10, atol=0)
    for block in (1, 3, 100):
        with pytest.MonkeyPatch.context() as m:
            m.setattr(prefilter, "WELCH_BLOCK", block)
            again = prefilter._pooled_spectra(pairs, fs, nper)
        for got, want in zip(again[1:], out[1:], strict=True):
            np.testing.assert_allclose(got, want, rtol=1e-13, atol=0)


def test_sincos_in_degrees_is_accurate_to_the_last_bits():
    """The polynomial sine/cosine of the total heave kernels against long-double values:
    every quadrant, the exact multiples of 45°, ±0, and angles far beyond a turn."""
    from hydrosync_core.methods.latency import heave

    rng = np.random.default_rng(11)
    deg = np.concatenate([rng.uniform(-720.0, 720.0, 200_000), np.arange(-720.0, 720.5, 0.5),
                          [0.0, -0.0, 45.0, -45.0, 135.0, 1e-300, 89.99999999999999]])
    per_degree = np.longdouble("3.14159265358979323846264338327950288") / 180
    rad = deg.astype(np.longdouble) * per_degree
    got = np.array([heave._sincos_deg(float(d)) for d in deg[:2000]])
    window = heave._total_heave_deg_nb1(np.zeros(deg.size), deg, np.zeros(deg.size),
                                        0.0, 1.0, 0.0)
    # y = 1 m: total heave = -(cos p · sin r) = -sin(roll) at pitch 0. Two units in the
    # last place at most (libm's sin(d·π/180) in double is off by up to 1.1e-15).
    np.testing.assert_allclose(-window, np.sin(rad).astype(float), rtol=0, atol=2.5e-16)
    np.testing.assert_allclose(got[:, 0], np.sin(rad[:2000]).astype(float), rtol=0,
                               atol=2.5e-16)
    np.testing.assert_allclose(got[:, 1], np.cos(rad[:2000]).astype(float), rtol=0,
                               atol=2.5e-16)
    # z = -1 m (antenna above): total heave = cos p·cos r - 1 at the sample's angles.
    pitch = rng.uniform(-90.0, 90.0, deg.size)
    both = heave._total_heave_deg_nb1(np.zeros(deg.size), deg, pitch, 0.0, 0.0, -1.0)
    prad = pitch.astype(np.longdouble) * per_degree
    np.testing.assert_allclose(both, (np.cos(prad) * np.cos(rad) - 1).astype(float),
                               rtol=0, atol=6e-16)
    # Angles beyond LARGE_DEG (never a measurement, but finite input must not go wrong).
    huge = np.array([3.6e14 + 30.0, -7.2e20, 1e300, 30.0])
    turned = np.fmod(huge, 360.0)
    np.testing.assert_array_equal(
        heave._total_heave_deg_nb1(np.zeros(4), huge, np.zeros(4), 0.0, 1.0, 0.0),
        heave._total_heave_deg_nb1(np.zeros(4), turned, np.zeros(4), 0.0, 1.0, 0.0))
    t = np.arange(4.0)
    np.testing.assert_array_equal(
        total_heave_at(t, t, np.zeros(4), huge, np.zeros(4), (0.0, 1.0, 0.0)),
        total_heave_at(t, t, np.zeros(4), turned, np.zeros(4), (0.0, 1.0, 0.0)))


def test_compiled_filter_steps_give_numpys_numbers_to_the_last_bit():
    """prefilter.spectrum/filtered (compiled element-wise steps, fastfilter) against the
    numpy expressions they replace, written out here: every window length parity,
    padding wider than the series, kept bins, crops and an output buffer."""
    from hydrosync_core.methods.latency import prefilter

    def numpy_bins(x, spec):
        kc = np.arange(x.size, dtype=float) - 0.5 * (x.size - 1)
        left = spec.left
        y = np.pad(x - (spec.intercept + spec.slope * kc), (left, spec.size - x.size - left),
                   mode="symmetric")
        return np.fft.rfft(y)

    def numpy_filtered(spec, gains, crop=slice(None)):
        lo, hi, _ = crop.indices(spec.n)
        product = spec.bins * gains[0][:spec.bins.size]
        series = np.fft.irfft(product, spec.size)[spec.left + lo:spec.left + hi]
        kc = np.arange(lo, hi, dtype=float) - 0.5 * (spec.n - 1)
        return series + (spec.intercept + spec.slope * kc) * gains[1]

    rng = np.random.default_rng(21)
    for n in (4, 5, 7, 64, 1199, 1200, 18001, 36450, 70001):
        x = np.cumsum(rng.normal(size=n)) + 0.3 * np.arange(n)
        g = prefilter.response_gains(lambda f: prefilter.antialias_response(f, 3.0),
                                     prefilter.next_fast_len(2 * n), 0.01)
        crop = slice(n // 5, n - n // 7)
        spec = prefilter.spectrum(x)
        np.testing.assert_array_equal(spec.bins, numpy_bins(x, spec))
        np.testing.assert_array_equal(prefilter.filtered(spec, g), numpy_filtered(spec, g))
        np.testing.assert_array_equal(prefilter.filtered(spec, g, crop),
                                      numpy_filtered(spec, g, crop))
        buf = np.full(x.size + 3, 7.0)
        np.testing.assert_array_equal(prefilter.filtered(spec, g, crop, out=buf),
                                      numpy_filtered(spec, g, crop))
        head = spec.head(min(spec.bins.size, int(0.6 * spec.bins.size) + 1))
        cut = (g[0] * (np.arange(g[0].size) < head.bins.size), g[1])
        np.testing.assert_array_equal(prefilter.filtered(head, cut, crop),
                                      numpy_filtered(head, cut, crop))
    assert prefilter._sum_of_squares(1199) == float((prefilter._centred_index(1199) ** 2).sum())
    assert prefilter._sum_of_squares(1200) == float((prefilter._centred_index(1200) ** 2).sum())


def test_compiled_detrend_gives_numpys_numbers_to_the_last_bit():
    """The compiled linear detrend (its sums replay numpy's pairwise summation) against
    the numpy expressions, for every size class of that summation."""
    from hydrosync_core.methods.latency import detrend as dt

    rng = np.random.default_rng(31)
    sizes = list(range(2, 140)) + [255, 256, 257, 1199, 1200, 3600, 8193, 36451]
    for n in sizes:
        values = rng.normal(size=n) * 10.0 ** rng.uniform(-3, 5, n)
        assert dt._sum(values) == np.add.reduce(values)
        t = 1.7e9 + np.cumsum(rng.uniform(0.05, 0.15, n))
        h = 40.0 + rng.normal(size=n) + 0.01 * (t - t[0])
        for degree in (0, 1):
            got = dt.detrend(t, h, degree)
            ref = dt._detrend_linear(t - t.mean(), h, degree)
            np.testing.assert_array_equal(got[0], ref[0])
            np.testing.assert_array_equal(got[1], ref[1])
    # Constant times: no slope; other dtypes take the numpy expressions.
    flat = dt.detrend(np.full(5, 3.0), np.arange(5.0), 1)
    assert flat[1][1] == 0.0 and np.allclose(flat[0], np.arange(5.0) - 2.0)
    ints = dt.detrend(np.arange(50), np.arange(50.0) * 2 + 1, 1)
    np.testing.assert_allclose(ints[0], 0.0, atol=1e-12)


def test_largest_step_is_the_largest_difference():
    rng = np.random.default_rng(41)
    for n in (2, 3, 1000):
        t = np.cumsum(rng.uniform(0.001, 0.2, n))
        t[n // 2:] += 3.0  # a gap
        for series in (t, t[::2] if n > 3 else t, t.astype(np.float32)):  # strided, float32
            assert fastscan.largest_step(series) == np.diff(series).max()
