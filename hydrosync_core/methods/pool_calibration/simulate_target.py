"""Design of the pool calibration target (seed 003, step 1) as a ``target.json`` dict.

Frame: target ENU, metres, origin at the target centre, Y (north) along the wall, X
(east) perpendicular to it, Z up. The wall face is the plane ``x = 0`` facing west
(``-x``), the side the vessel passes on with its starboard side to the target; it always
crosses the water level. Triangular block columns stand on both sides (north ``N1, N2 ...``
beyond ``y = +wall_length/2``, south ``S1, S2 ...`` beyond ``-wall_length/2``) at equal
spacing, flush with the wall plane and sticking out towards the vessel. Each block is a
vertical prism whose horizontal cross-section is a right triangle: one vertical face
perpendicular to the wall (normal along Y), one oblique vertical face (facing the vessel
and the far end), top and bottom horizontal faces. The first block of the ``low_side``
column sits lower than the first block of the other column (patent step 1).

Two kinds of target (``kind``), both occurring in practice and often mixed:

* ``"patent"`` — the patent's own target (steps 3.3 and 4.2): every block exists twice, as
  an above-water block (``N1_up_*``, seen only by the laser scanner) and a below-water block
  of the same shape and orientation (``N1_dn_*``, seen only by the multibeam) at design
  heights, optionally shifted along the wall by ``twin_shift``. Only the wall crosses the
  water. A below-water face is compared with its above-water twin's laser plane moved by
  the design translation.
* ``"crossing"`` — blocks that cross the water level (seen by the scanner above and by the
  multibeam below, the same face); the low first block's top lies below water and is
  compared with an above-water top of the same shape (the design height difference).
* ``"mixed"`` — the north column crosses the water, the south column is of the patent kind.
"""

from __future__ import annotations

import numpy as np

KINDS = ("patent", "crossing", "mixed")


def _block(name: str, y0: float, sign: float, depth: float, length: float,
           z_bottom: float, z_top: float) -> list[dict]:
    """Faces of one triangular prism block; *sign* +1 north side, -1 south side.

    Triangle (plan view, ENU): A = (0, y0) on the wall line, B = (-depth, y0) towards the
    vessel, C = (0, y0 + sign*length) further along the wall line. AB is the perpendicular
    face, BC the oblique face, CA lies in the wall plane (not a visible face).
    """
    ax, ay = 0.0, y0
    bx, by = -depth, y0
    cx, cy = 0.0, y0 + sign * length
    faces = [
        {"name": f"{name}_perpendicular",
         "corners": [[ax, ay, z_bottom], [bx, by, z_bottom], [bx, by, z_top], [ax, ay, z_top]]},
        {"name": f"{name}_oblique",
         "corners": [[bx, by, z_bottom], [cx, cy, z_bottom], [cx, cy, z_top], [bx, by, z_top]]},
        {"name": f"{name}_top",
         "corners": [[ax, ay, z_top], [bx, by, z_top], [cx, cy, z_top]]},
        {"name": f"{name}_bottom",
         "corners": [[ax, ay, z_bottom], [cx, cy, z_bottom], [bx, by, z_bottom]]},
    ]
    for f in faces:
        f["corners"] = [[round(float(v), 6) for v in c] for c in f["corners"]]
    return faces


def build_target(
    *,
    kind: str = "patent",
    wall_length: float = 6.0,
    wall_bottom: float = -5.0,
    wall_top: float = 2.0,
    blocks_per_side: int = 2,
    block_gap: float = 0.3,
    block_depth: float = 1.0,
    block_length: float = 1.5,
    block_spacing: float = 0.6,
    block_bottom: float = -4.5,
    block_top: float = 1.3,
    low_block_top: float = -3.0,
    up_bottom: float = 0.4,
    up_top: float = 1.9,
    down_top: float = -3.0,
    twin_shift: float = 0.0,
    low_side: str = "S",
    low_drop: float = 0.3,
    water_level: float = 0.0,
) -> dict:
    """Return the ``target.json`` document of a seed-003 calibration target.

    Parameters
    ----------
    kind : "patent", "crossing" or "mixed" (see the module docstring).
    wall_length, wall_bottom, wall_top : float
        Wall face extent along Y (m) and its bottom/top heights (m, ENU up).
    blocks_per_side : int
        Number of triangular blocks in each column (north and south).
    block_gap, block_spacing : float
        Gap between the wall end and the first block, and between successive blocks, m.
    block_depth, block_length : float
        Plan-view legs of the right triangle: across (towards the vessel) and along Y, m.
    block_bottom, block_top, low_block_top : float
        Crossing blocks: bottom and top heights (m); top of the low side's first block
        (below water).
    up_bottom, up_top, down_top : float
        Patent blocks: bottom and top heights (m) of the above-water block, top height of
        its below-water twin (same height, so the same shape).
    twin_shift : float
        Patent blocks: the below-water twin is shifted by this much along the column (m).
    low_side, low_drop : "N" or "S", float
        Patent blocks: the first block pair of this side sits *low_drop* m lower.
    water_level : float
        Water level, m.
    """
    if kind not in KINDS:
        raise ValueError(f"kind must be one of {KINDS}")
    if not (wall_bottom < water_level < wall_top):
        raise ValueError("the wall must cross the water level")
    if kind != "patent":
        if not (block_bottom < water_level < block_top):
            raise ValueError("the blocks must cross the water level")
        if not (block_bottom < low_block_top < water_level):
            raise ValueError("the low block's top must be below water and above its bottom")
    if kind != "crossing":
        if not (water_level < up_bottom - low_drop < up_top - low_drop):
            raise ValueError("the above-water blocks must stay above water")
        if not (wall_bottom <= down_top - (up_top - up_bottom) - low_drop
                and down_top < water_level):
            raise ValueError("the below-water blocks must stay below water, above the floor")
        if abs(twin_shift) > block_spacing:
            raise ValueError("the twin shift must not exceed the block spacing")
    half = wall_length / 2.0
    faces = [{"name": "wall", "corners": [[0.0, -half, wall_bottom], [0.0, half, wall_bottom],
                                          [0.0, half, wall_top], [0.0, -half, wall_top]]}]
    step = block_length + block_spacing
    for side, sign in (("N", 1.0), ("S", -1.0)):
        patent = kind == "patent" or (kind == "mixed" and side == "S")
        for k in range(blocks_per_side):
            y0 = sign * (half + block_gap + k * step)
            if not patent:
                top = low_block_top if (side == "S" and k == 0) else block_top
                faces += _block(f"{side}{k + 1}", y0, sign, block_depth, block_length,
                                block_bottom, top)
                continue
            drop = low_drop if (side == low_side and k == 0) else 0.0
            faces += _block(f"{side}{k + 1}_up", y0, sign, block_depth, block_length,
                            up_bottom - drop, up_top - drop)
            faces += _block(f"{side}{k + 1}_dn", y0 + sign * twin_shift, sign, block_depth,
                            block_length, down_top - (up_top - up_bottom) - drop,
                            down_top - drop)
    return {"frame": "ENU", "water_level_m": float(water_level), "faces": faces}


def random_target(rng: np.random.Generator, kind: str | None = None) -> dict:
    """A target drawn at random: kind, number and size of blocks, spacing, which side's
    first block is lower and by how much, wall height, water level, twin heights/shift."""
    kind = kind or str(rng.choice(KINDS))
    water = float(rng.uniform(-0.4, 0.4))
    floor = water - float(rng.uniform(4.0, 5.5))
    depth = float(rng.uniform(0.7, 1.2))
    length = float(rng.uniform(1.0, 1.9))
    spacing = float(rng.uniform(0.4, 1.0))
    up_bottom = water + float(rng.uniform(0.8, 1.1))
    height = float(rng.uniform(0.8, 1.8))
    drop = float(rng.uniform(0.1, 0.6))
    down_top = max(water - float(rng.uniform(2.4, 3.2)), floor + height + drop + 0.05)
    kw = dict(
        kind=kind, water_level=water, wall_length=float(rng.uniform(4.0, 8.0)),
        wall_bottom=floor, wall_top=water + float(rng.uniform(1.0, 2.2)),
        blocks_per_side=int(rng.integers(1, 4)), block_gap=float(rng.uniform(0.2, 0.5)),
        block_depth=depth, block_length=length, block_spacing=spacing,
        block_bottom=floor, block_top=water + float(rng.uniform(0.8, 1.6)),
        low_block_top=water - float(rng.uniform(2.2, 3.2)),
        up_bottom=up_bottom, up_top=up_bottom + height, down_top=down_top,
        twin_shift=float(rng.choice([0.0, rng.uniform(-0.3, 0.3)])) if spacing > 0.3 else 0.0,
        low_side=str(rng.choice(["N", "S"])), low_drop=drop)
    return build_target(**kw)
