"""Campaign processing: many projects, one command (``hydrosync batch CAMPAIGN.toml``).

A campaign file (TOML, ``docs/formats.md`` "Campaign file") names projects — a list, glob
patterns, or raw-file sets imported into new projects by an import recipe — the analyses
to run on each with their parameters (validated by each analysis's parameter schema), and
the outputs (a PDF per project, a campaign summary as CSV and HTML).

* :mod:`~hydrosync_core.campaign.config` reads and checks the file and plans the steps;
* :mod:`~hydrosync_core.campaign.steps` is what runs on a worker: import, one analysis,
  report — each opens the project with its write lock, works, saves atomically, closes;
* :mod:`~hydrosync_core.campaign.engine` submits the steps to ``dask.distributed`` (a
  ``LocalCluster`` by default, an existing scheduler on request) and follows them;
* :mod:`~hydrosync_core.campaign.summary` writes ``summary.csv`` and ``summary.html``.

Dask is imported only by the engine, when a campaign actually runs.
"""

from hydrosync_core.campaign.config import Campaign, load_campaign

__all__ = ["Campaign", "load_campaign"]
