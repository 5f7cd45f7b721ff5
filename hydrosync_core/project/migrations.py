"""Sequential integer migrations of the project schema.

``MIGRATIONS[n]`` upgrades an open :class:`~hydrosync_core.project.model.Project` from
schema ``n`` to ``n + 1`` in memory; the upgraded file is written at the next save (the
original is never modified in place). Version 0 denotes the pre-release layout in which
results lived under ``/analysis`` and the vessel sheet under ``/config``.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

from hydrosync_core.errors import ProjectFormatError
from hydrosync_core.project.schema import SCHEMA_VERSION

if TYPE_CHECKING:
    from hydrosync_core.project.model import Project


def _v0_to_v1(project: Project) -> None:
    """Rename the pre-release groups ``/config`` → ``/vessel``, ``/analysis`` → ``/results``."""
    for old, new in (("config", "vessel"), ("analysis", "results")):
        if project.exists(old):
            project.move(old, new)


MIGRATIONS: dict[int, Callable[[Project], None]] = {0: _v0_to_v1}


def migrate(project: Project, from_version: int) -> int:
    """Upgrade *project* from *from_version* to :data:`SCHEMA_VERSION`.

    Returns the number of migration steps applied. Raises
    :class:`ProjectFormatError` for a file newer than this software.
    """
    if from_version > SCHEMA_VERSION:
        raise ProjectFormatError(
            project.path,
            f"project schema version {from_version} is newer than this HydroSync "
            f"(supports up to {SCHEMA_VERSION}); upgrade HydroSync to open it",
        )
    steps = 0
    for version in range(from_version, SCHEMA_VERSION):
        if version not in MIGRATIONS:
            raise ProjectFormatError(project.path, f"no migration from schema {version}")
        MIGRATIONS[version](project)
        steps += 1
    return steps
