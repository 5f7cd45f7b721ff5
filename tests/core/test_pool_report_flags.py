"""The pool section flags in the PDF summary what the panel flags (#26): a σ beyond its
threshold and a parameter the data do not determine, on the summary row of that parameter."""

from hydrosync_core.methods.pool_calibration.report_section import flags


class _Project:
    def __init__(self, result: dict) -> None:
        self.result = result

    def get_json(self, path: str, default=None):
        return self.result


def test_flagged_and_undetermined_parameters_are_flagged_on_their_summary_rows():
    got = flags(_Project({"flagged": {"pitch": "σ = 0.016° exceeds 0.01°"},
                          "undetermined": {"lever_z": "no block top seen"}}))
    assert got == {
        "Boresight pitch (final, 1\u03c3)": "σ = 0.016° exceeds 0.01°",
        "Lever arm z (down) (final, 1\u03c3)": "not determined by the data (no block top "
                                                "seen); the coarse value is kept",
    }


def test_nothing_flagged_gives_no_flags():
    assert flags(_Project({})) == {}
