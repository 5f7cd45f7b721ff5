"""The HDF5 project schema: version, fixed group names, dataset creation options.

See ``docs/project-format.md`` for the full description.
"""

from __future__ import annotations

SCHEMA_VERSION = 1
"""Current integer schema version; older files are upgraded by ``migrations``."""

FORMAT_NAME = "HydroSync project"

VESSEL = "vessel"
RAW = "raw"
RESULTS = "results"

RAW_GNSS = "raw/gnss"
RAW_ATTITUDE = "raw/attitude"
RAW_LINES = "raw/lines"
RAW_POOL = "raw/pool"

TABLE_KIND = "table"
"""Value of the ``kind`` attribute on a group holding one 1-D dataset per column."""

JSON_ATTR = "json"
"""Attribute holding a JSON document (parameters, setup, target design)."""

CHUNK_MIN_ELEMENTS = 4096
"""Arrays smaller than this are stored contiguous: chunking tiny arrays wastes space."""


def dataset_options(shape: tuple[int, ...]) -> dict:
    """Chunking/compression options for a new dataset of *shape*.

    Large arrays are chunked (about 1 MiB per chunk, h5py's automatic shape) and
    gzip-compressed with the shuffle filter; both are standard HDF5 filters readable by
    any HDF5 tool.
    """
    size = 1
    for n in shape:
        size *= n
    if size < CHUNK_MIN_ELEMENTS:
        return {}
    return {"chunks": True, "compression": "gzip", "compression_opts": 4, "shuffle": True}
