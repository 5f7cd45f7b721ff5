"""The install-time warm-up compiles (or finds cached) the latency kernels and never fails."""

from __future__ import annotations

from hydrosync_core import warmup


def test_warmup_runs_the_latency_kernels(capsys):
    assert warmup.main() == 0
    assert "compiled kernels cached" in capsys.readouterr().out


def test_warmup_never_fails_an_install(monkeypatch, capsys):
    def broken():
        raise RuntimeError("no compiler here")

    monkeypatch.setattr(warmup, "compile_latency_kernels", broken)
    assert warmup.main() == 0
    assert "on first use" in capsys.readouterr().err
