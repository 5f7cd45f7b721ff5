"""Demo data for the Pool Calibration plugin: a simulated session written into a project.

A session of three passes at 4, 5.5 and 7 m, each recorded as its own files (pass 1 under
``raw/pool/``, the others under ``raw/pool/passes/<k>/``), of one built target, with one
shared laser scan; they are adjusted jointly.

The demo target is the patent's own kind (CN 105425246 B, step 1): a central wall crossing
the water and triangular blocks on both sides, each existing as an above-water block (seen
by the laser scanner) and a below-water twin of the same shape and orientation at design
heights (seen by the multibeam).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from hydrosync_core.methods.pool_calibration.project_run import PASSES
from hydrosync_core.methods.pool_calibration.simulate import PoolPassConfig, simulate_pool_pass
from hydrosync_core.methods.pool_calibration.simulate_target import build_target
from hydrosync_core.progress import report
from hydrosync_core.project.vessel import set_sensor

#: Three passes at 4, 5.5 and 7 m (headings +3°, -3°, 0°), a multibeam at 256 beams and
#: 20 Hz, along a patent target with three block pairs on each side of the wall.
DEMO_CONFIG = PoolPassConfig(
    target_kind="patent", ranges_m=(4.0, 5.5, 7.0), headings_deg=(3.0, -3.0, 0.0),
    ping_rate_hz=20.0,
    target=build_target(kind="patent", blocks_per_side=3, block_depth=1.2, block_length=1.3))


def fill_demo(project, seed: int = 0, progress=None,
              config: PoolPassConfig | None = None) -> dict:
    """Write raw/pool/{lidar, mbes, ins, setup, target}, the further passes under
    raw/pool/passes/<k>/{mbes, ins} and the vessel sheet; return the truth.

    *config* (optional) overrides the simulation settings (tests use smaller data sets);
    each of its ``ranges_m`` becomes a pass of its own.
    """
    cfg = replace(config or DEMO_CONFIG, build_seed=seed)
    headings = cfg.headings_deg or (0.0,) * len(cfg.ranges_m)
    sims = []
    for k, rng_m in enumerate(cfg.ranges_m):
        report(progress, k / len(cfg.ranges_m), f"simulating pool calibration pass {k + 1}")
        sims.append(simulate_pool_pass(replace(cfg, ranges_m=(rng_m,),
                                               headings_deg=(headings[k % len(headings)],)),
                                       seed=seed + 101 * k))
    sim = sims[0]
    project.put("raw/pool/lidar", sim["lidar"],
                attrs={"frame": "target ENU", "units": "m", "source": "simulated"})
    for k, s in enumerate(sims):
        base = "raw/pool" if k == 0 else f"{PASSES}/{k + 1}"
        project.put_table(f"{base}/mbes", {n: np.asarray(v) for n, v in s["mbes"].items()},
                          source="simulated")
        project.put_table(f"{base}/ins", {n: np.asarray(v) for n, v in s["ins"].items()},
                          source="simulated")
    project.put_json("raw/pool/setup", sim["setup"])
    project.put_json("raw/pool/target", sim["target"])
    b = sim["setup"]["boresight_deg"]
    la = sim["setup"]["lever_arm_m"]
    set_sensor(project, "ins", [0.0, 0.0, 0.0])
    set_sensor(project, "multibeam", [la["x"], la["y"], la["z"]], angles_deg=b,
               note="coarse values (installation drawing)")
    report(progress, 1.0, "pool demo data written")
    return {k: sim["truth"][k] for k in ("boresight_deg", "lever_arm_m")}
