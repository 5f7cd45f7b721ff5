"""The install-time warm-up compiles (or finds cached) the numba kernels and never fails."""

from __future__ import annotations

from hydrosync_core import warmup


def test_warmup_runs_every_compiled_module(capsys):
    assert warmup.main() == 0
    out = capsys.readouterr().out
    assert "compiled kernels cached" in out
    # Every analysis that declares a warm-up (spec.warmup), found through the registry.
    assert "Latency" in out and "GNSS/INS Smoother" in out


def test_warmup_never_fails_an_install(monkeypatch, capsys):
    def broken():
        raise RuntimeError("no compiler here")

    monkeypatch.setattr(warmup, "steps", lambda: [("Latency", broken),
                                                  ("GNSS/INS Smoother", broken)])
    assert warmup.main() == 0
    err = capsys.readouterr().err
    assert err.count("on first use") == 2 and "Latency" in err and "Smoother" in err


def test_one_failing_step_leaves_the_others(monkeypatch, capsys):
    ran = []

    def broken():
        raise RuntimeError("no compiler here")

    monkeypatch.setattr(warmup, "steps", lambda: [("Latency", broken),
                                                  ("GNSS/INS Smoother", lambda: ran.append(1))])
    assert warmup.main() == 0
    captured = capsys.readouterr()
    assert ran == [1] and "(GNSS/INS Smoother)" in captured.out
    assert "Latency kernels not compiled ahead" in captured.err
