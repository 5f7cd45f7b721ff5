"""GNSS Attitude plugin: heading, pitch and roll from an antenna array (Qt-free declaration).

Importing this module loads only :mod:`hydrosync_core.plugins.spec`; the method, its
parameter schema and the panel are named by dotted path and imported when used.
"""

from hydrosync_core.methods.gnss_attitude import VERSION
from hydrosync_core.plugins.spec import DataKind, PluginSpec

CORE = "hydrosync_core.methods.gnss_attitude"

SPEC = PluginSpec(
    id="gnss_attitude",
    name="GNSS Attitude",
    run=f"{CORE}.project_run:run",
    panel="plugins.gnss_attitude.panel:GnssAttitudePanel",
    params=f"{CORE}.params:GnssAttitudeParams",
    cli=f"{CORE}.cli:register",
    data_kinds=(
        DataKind("pos", "RTKLIB solution file .pos of one antenna (llh/xyz/enu; the file "
                 "stem names the antenna)", "raw/gnss_attitude/pos",
                 "hydrosync_core.importers.rtklib_pos:store_pos", "custom",
                 repeatable="one .pos per antenna"),
        DataKind("geo", "position file .geo of one antenna (calendar time, lat, lon, h, "
                 "3 sigma; no quality flag; the file stem names the antenna)",
                 "raw/gnss_attitude/pos",
                 "hydrosync_core.importers.geo_positions:store_geo", "custom",
                 repeatable="one .geo per antenna"),
        DataKind("antenna_csv", "antenna_positions.csv: time, antenna, x, y, z (ECEF m), "
                 "quality (GGA) of every antenna of the array",
                 "raw/gnss_attitude/pos",
                 "hydrosync_core.importers.antenna_csv:store_antenna_csv", "custom"),
        DataKind("antennas", "antennas.json: antenna coordinates in the body frame (FRD, m)",
                 "raw/gnss_attitude/antennas", f"{CORE}.antennas:read_antennas_json", "json"),
    ),
    requires=("raw/gnss_attitude/pos", "raw/gnss_attitude/antennas"),
    description="Heading, pitch and roll from three or more GNSS antennas: direct method and "
    "iterative least squares (Liu et al.), closed-form Wahba cross-check, precision "
    "prediction.",
    demo=f"{CORE}.demo:fill_demo",
    report_section=f"{CORE}.report_section:section",
    order=30,
    version=VERSION,
)
