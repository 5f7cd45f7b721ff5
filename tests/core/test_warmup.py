"""The install-time warm-up compiles (or finds cached) the numba kernels and never fails."""

from __future__ import annotations

from hydrosync_core import warmup


def test_warmup_runs_every_compiled_module(capsys):
    assert warmup.main() == 0
    out = capsys.readouterr().out
    assert "compiled kernels cached" in out
    assert "latency" in out and "GNSS/INS smoother" in out


def test_warmup_never_fails_an_install(monkeypatch, capsys):
    def broken():
        raise RuntimeError("no compiler here")

    monkeypatch.setattr(warmup, "STEPS", (("latency", broken), ("GNSS/INS smoother", broken)))
    assert warmup.main() == 0
    err = capsys.readouterr().err
    assert err.count("on first use") == 2 and "latency" in err and "smoother" in err


def test_one_failing_step_leaves_the_others(monkeypatch, capsys):
    ran = []

    def broken():
        raise RuntimeError("no compiler here")

    monkeypatch.setattr(warmup, "STEPS", (("latency", broken),
                                          ("GNSS/INS smoother", lambda: ran.append(1))))
    assert warmup.main() == 0
    captured = capsys.readouterr()
    assert ran == [1] and "(GNSS/INS smoother)" in captured.out
    assert "latency kernels not compiled ahead" in captured.err
