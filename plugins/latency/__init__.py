"""Latency plugin: delay between GNSS heights and attitude/heave (Qt-free declaration).

Importing this module loads only :mod:`hydrosync_core.plugins.spec`; the method, its
parameter schema and the panel are named by dotted path and imported when used.
"""

from hydrosync_core.methods.latency import VERSION
from hydrosync_core.plugins.spec import DataKind, PluginSpec, Trend, TrendSeries

CORE = "hydrosync_core.methods.latency"
READERS = "hydrosync_core.importers"
SEVERAL_LOGS = ("several logs of one kind, also a quoted glob such as 'day/*.log', become "
                "one table in time order")

SPEC = PluginSpec(
    id="latency",
    name="Latency",
    run=f"{CORE}.project_run:run",
    panel="plugins.latency.panel:LatencyPanel",
    params=f"{CORE}.params:LatencyParams",
    cli=f"{CORE}.cli:register",
    data_kinds=(
        DataKind("gnss", "GNSS heights CSV (time, height[, lat, lon, quality])", "raw/gnss",
                 f"{READERS}.survey_csv:read_gnss_csv"),
        DataKind("attitude", "attitude CSV (time, roll, pitch, heading, heave)",
                 "raw/attitude", f"{READERS}.survey_csv:read_attitude_csv",
                 options=("heave_positive",)),
        DataKind("lines", "survey lines CSV (name, start, end)", "raw/lines",
                 f"{READERS}.survey_csv:read_lines_csv"),
        DataKind("gnss_log", "NMEA GNSS log (GGA / PTNL,GGK [+GST, ZDA]; logger time tags "
                 "allowed)", "raw/gnss", f"{READERS}.log_import:store_gnss_log", "custom",
                 options=("empty_geoid",), repeatable=SEVERAL_LOGS),
        DataKind("attitude_log", "NMEA motion log (PASHR / PSXN,23 / TSS1)", "raw/attitude",
                 f"{READERS}.log_import:store_attitude_log", "custom",
                 options=("heave_positive",), repeatable=SEVERAL_LOGS),
    ),
    requires=("raw/gnss", "raw/attitude", "raw/lines"),
    icon="latency.svg",
    description="Delay of the GNSS time tags relative to the attitude/heave time tags, "
    "by correlating detrended RTK heights with total heave (Qi et al. 2010).",
    demo=f"{CORE}.demo:fill_demo",
    report_section=f"{CORE}.report_section:section",
    order=10,
    warmup=f"{CORE}.warmup:compile_kernels",
    trends=(Trend("Latency Δt (GNSS tags late) per survey day, 95 % interval", "s",
                  (TrendSeries("Δt", "latency_s", low="ci95_low", high="ci95_high"),)),),
    version=VERSION,
)
