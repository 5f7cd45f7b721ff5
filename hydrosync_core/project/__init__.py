"""HDF5 project file: schema, atomic store, migrations, model."""

from hydrosync_core.project.model import NodeInfo, Project, default_vessel

__all__ = ["NodeInfo", "Project", "default_vessel"]
