#!/usr/bin/env python3
"""Build the hostile-file corpus of issue #9 (and optionally import every file).

Files a careless colleague or a broken device produces, each meant for one import kind
(``hydrosync import P.h5 --KIND FILE``): LAZ files whose chunk table makes the LAZ decoder
abort the process, a CSV field of 200 000 characters, a 400-digit JSON integer, JSON
nested 100 000 deep, a PLY ``element vertex many``, physically impossible values (roll
1e308, LAS scale 1e300, PLY vertex 1e308), rows with extra fields, duplicated and
overlapping survey lines, binary garbage. Every one must end with exit 2 and exactly one
line on stderr that quotes at most ~120 characters of the file.

    python scripts/build_hostile_corpus.py OUT_DIR [--run]
"""

from __future__ import annotations

import argparse
import io
import random
import struct
import sys
from pathlib import Path

import numpy as np

GNSS_HEAD = "time,height\n"
ATT_HEAD = "time,roll,pitch,heading,heave\n"


def _gnss_rows(n: int = 20) -> str:
    return "".join(f"{100 + i},{20 + 0.01 * i}\n" for i in range(n))


def _att_rows(n: int = 20, roll: str = "1.0") -> str:
    return "".join(f"{100 + 0.1 * i},{roll if i == 7 else 0.5},0.2,90.0,0.1\n" for i in range(n))


def _las(scale: float = 0.001, compressed: bool = False, n: int = 3000) -> bytes:
    import laspy

    header = laspy.LasHeader(point_format=1, version="1.2")
    header.scales = [0.001, 0.001, 0.001]
    header.offsets = [0.0, 0.0, 0.0]
    las = laspy.LasData(header)
    rng = np.random.default_rng(5)
    las.x, las.y, las.z = (rng.uniform(-5, 5, n) for _ in range(3))
    las.gps_time = np.arange(n) * 0.01
    out = io.BytesIO()
    las.write(out, do_compress=compressed)
    data = bytearray(out.getvalue())
    if scale != 0.001:
        struct.pack_into("<d", data, 131, scale)
    return bytes(data)


def _laz_chunk(mode: str) -> bytes:
    data = bytearray(_las(compressed=True, n=60000))
    start = struct.unpack_from("<I", data, 96)[0]
    table = struct.unpack_from("<q", data, start)[0]
    if mode == "count":
        struct.pack_into("<I", data, table + 4, 0x7FFFFFFF)
    elif mode == "offset":
        struct.pack_into("<q", data, start, len(data) * 7)
    elif mode == "entries":
        rng = random.Random(6)  # garbled chunk sizes: lazrs panics ("capacity overflow")
        for i in range(table + 8, len(data)):
            data[i] = rng.randrange(256)
    elif mode == "truncated":
        data = data[: len(data) // 2]
    return bytes(data)


def _nested(depth: int) -> str:
    return '{"boresight_deg": ' + "[" * depth + "]" * depth + "}"


def _setup(roll: str) -> str:
    return ('{"boresight_deg": {"roll": ' + roll + ', "pitch": 0.0, "yaw": 0.0},\n'
            ' "lever_arm_m": {"x": 1.2, "y": 2.45, "z": 1.8}}\n')


def _ply(vertex: str = "3", value: str = "1.0", newline: bool = True, body: bool = True) -> bytes:
    head = f"ply\nformat ascii 1.0\nelement vertex {vertex}\nproperty float x\n" \
           "property float y\nproperty float z\nend_header"
    rows = f"0 0 0\n1 1 1\n{value} 2 2\n" if body else ""
    return (head + ("\n" if newline else "") + rows).encode()


def cases() -> list[tuple[str, str, bytes]]:
    """(file name, import kind, content) of every hostile file."""
    long_field = "7" * 200_000
    rng = random.Random(9)
    garbage = bytes(rng.randrange(256) for _ in range(4000))
    return [
        ("laz-chunk-count.laz", "lidar", _laz_chunk("count")),
        ("laz-chunk-offset.laz", "lidar", _laz_chunk("offset")),
        ("laz-chunk-entries.laz", "lidar", _laz_chunk("entries")),
        ("laz-truncated.laz", "lidar", _laz_chunk("truncated")),
        ("las-scale-1e300.las", "lidar", _las(scale=1e300)),
        ("las-header-only.las", "lidar", _las()[:200]),
        ("ply-vertex-many.ply", "lidar", _ply(vertex="many")),
        ("ply-vertex-1e308.ply", "lidar", _ply(value="1e308")),
        ("ply-no-line-end.ply", "lidar", _ply(newline=False, body=False)),
        ("ply-no-vertices.ply", "lidar", _ply(body=False)),
        ("csv-long-field.csv", "gnss",
         (GNSS_HEAD + _gnss_rows(5) + f"106,{long_field}\n").encode()),
        ("csv-long-quoted.csv", "gnss",
         (GNSS_HEAD + _gnss_rows(5) + f'106,"{long_field},{long_field}"\n').encode()),
        ("csv-long-header.csv", "gnss", (f"time,{long_field}\n" + _gnss_rows(3)).encode()),
        ("csv-long-text.csv", "gnss",
         (GNSS_HEAD + _gnss_rows(5) + f"106,x{long_field}\n").encode()),
        ("csv-header-only.csv", "gnss", GNSS_HEAD.encode()),
        ("csv-extra-fields.csv", "gnss", (GNSS_HEAD + _gnss_rows(5) + "106,20.5,99\n").encode()),
        ("csv-binary.csv", "gnss", garbage),
        ("attitude-roll-1e308.csv", "attitude", (ATT_HEAD + _att_rows(roll="1e308")).encode()),
        ("lines-duplicated.csv", "lines",
         b"name,start,end\nL1,100,200\nL2,300,400\nL1b,100,200\n"),
        ("lines-overlap.csv", "lines", b"name,start,end\nL1,100,200\nL2,150,260\n"),
        ("lines-long-name.csv", "lines", f"name,start,end\n{long_field},1,2\n".encode()),
        ("setup-400-digits.json", "setup", _setup("1" * 400).encode()),
        ("setup-5000-digits.json", "setup", _setup("9" * 5000).encode()),
        ("setup-roll-1e308.json", "setup", _setup("1e308").encode()),
        ("setup-nested.json", "setup", _nested(100_000).encode()),
        ("target-long-name.json", "target",
         ('{"faces": [{"name": "' + long_field
          + '", "corners": [[0,0,0],[1,0,0],[0,1,0]]}]}').encode()),
        ("vessel-nested.json", "vessel", ('{"sensors": ' + "[" * 50_000 + "]" * 50_000
                                          + "}").encode()),
        ("vessel-offset-1e308.json", "vessel",
         b'{"sensors": {"gnss": {"offset_m": [1e308, 0, 0]}}}'),
        ("nmea-binary.log", "gnss_log", garbage),
        ("nmea-long-line.log", "gnss_log", ("$GPGGA," + long_field + "\n").encode()),
    ]


def build_corpus(folder: Path) -> list[tuple[str, Path]]:
    """Write every hostile file into *folder*; return (kind, path) pairs."""
    folder.mkdir(parents=True, exist_ok=True)
    out = []
    for name, kind, content in cases():
        path = folder / name
        path.write_bytes(content)
        out.append((kind, path))
    return out


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("out", type=Path, help="folder to build the corpus in")
    parser.add_argument("--run", action="store_true", help="import every file (subprocess)")
    args = parser.parse_args()
    corpus = build_corpus(args.out)
    print(f"{len(corpus)} hostile files in {args.out}")
    if not args.run:
        return 0
    import subprocess

    failed = 0
    for kind, path in corpus:
        project = path.with_suffix(".h5")
        done = subprocess.run([sys.executable, "-m", "hydrosync_core.cli", "import",
                               str(project), f"--{kind}", str(path)],
                              capture_output=True, text=True)
        lines = done.stderr.strip().splitlines()
        ok = done.returncode == 2 and len(lines) == 1 and len(lines[0]) <= 400
        failed += not ok
        print(f"{'ok  ' if ok else 'FAIL'} {path.name:<28} exit {done.returncode} "
              f"({len(lines)} line(s)) {lines[-1][:150] if lines else ''}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
