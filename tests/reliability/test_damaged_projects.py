"""Issue #9 item 5: damaged projects give exit 2 and one line naming the project file,
the HDF5 path and what is wrong; ``report`` shows a damaged section as "could not be
produced: <reason>", warns, and fails with ``--strict``.

The corpus is built by ``scripts/build_damaged_corpus.py`` (every kind of damage named
in the issue, and a few more).
"""

from __future__ import annotations

import pytest

from hydrosync_core.cli import main
from tests.core.test_report import pdf_pages
from tests.reliability.conftest import load_script, stderr_lines

corpus_script = load_script("build_damaged_corpus")


@pytest.fixture(scope="module")
def corpus(tmp_path_factory):
    folder = tmp_path_factory.mktemp("damaged")
    return {case.name: (case, path) for case, path in corpus_script.build_corpus(folder)}


def test_the_undamaged_base_works(corpus, capsys):
    _, path = next(iter(corpus.values()))
    base = path.with_name("base.h5")
    assert main(["latency", str(base)]) == 0
    assert main(["pool-calibrate", str(base)]) == 0
    capsys.readouterr()


@pytest.mark.parametrize("name", [c.name for c in corpus_script.CASES
                                  if c.command != "report"])
def test_damaged_project_is_exit_2_with_one_line(corpus, name, capsys, faults):
    case, path = corpus[name]
    code = main(corpus_script.argv_for(case, path))
    lines = stderr_lines(capsys.readouterr().err)
    ok = (code == 2 and len(lines) == 1 and str(path) in lines[0]
          and f"/{case.hdf5_path}" in lines[0] and len(lines[0]) <= 400)
    faults.record(f"damaged project: {case.command}", ok, f"{name}: {code} {lines}")
    assert ok, (code, lines)
    # What a project holds can still be listed; data that fail the read-back against
    # their checksums make it exit 2 with one INPUT DAMAGED line (issue #28).
    code = main(["info", str(path)])
    shown = capsys.readouterr()
    assert str(path) in shown.out.splitlines()[0]
    assert code == 0 or (code == 2 and len(stderr_lines(shown.err)) == 1
                         and "INPUT DAMAGED" in shown.err), (code, shown.err)


@pytest.mark.parametrize("name", [c.name for c in corpus_script.CASES
                                  if c.command == "report"])
def test_report_of_damaged_project_names_the_section(corpus, name, capsys, faults):
    case, path = corpus[name]
    pdf = path.with_suffix(".pdf")
    code = main(corpus_script.argv_for(case, path))
    captured = capsys.readouterr()
    warnings = [line for line in stderr_lines(captured.err) if "warning:" in line]
    text = " ".join(pdf_pages(pdf)) if pdf.exists() else ""
    # A damaged section says "could not be produced: <reason>", a damaged vessel sheet
    # "could not be read: <reason>" — in the PDF and in the warnings.
    ok = (code == 0 and len(warnings) >= 1 and "could not be" in warnings[0]
          and "could not be" in text and "warning(s)" in captured.out)
    pdf.unlink(missing_ok=True)
    strict = main(corpus_script.argv_for(case, path, strict=True))
    lines = stderr_lines(capsys.readouterr().err)
    ok_strict = (strict == 2 and len(lines) == 1 and "--strict" in lines[0]
                 and not pdf.exists())
    faults.record("damaged project: report", ok and ok_strict,
                  f"{name}: {code} {warnings} / {strict} {lines}")
    assert ok, (code, warnings, captured.out)
    assert ok_strict, (strict, lines)
