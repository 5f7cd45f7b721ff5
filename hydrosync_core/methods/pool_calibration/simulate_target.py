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
* ``"prism"`` — the patent's target as built by others (:func:`prism_target`): every block
  a full prism (top, underside, three sides, one of them against the wall plane), the
  below-water prism of another height than the above-water one (coplanar sides, parallel
  tops), optionally on a plinth (a wider, lower slab under it), shifted along the column
  (a horizontal design offset), with a block missing or explicit twin declarations.
"""

from __future__ import annotations

import numpy as np

KINDS = ("patent", "crossing", "mixed", "prism")


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


def _prism(name: str, tri: np.ndarray, z0: float, z1: float) -> list[dict]:
    """Faces of a vertical prism over the plan triangle *tri* (3, 2) from z0 to z1: top,
    underside and the three sides (named side0..2 after the triangle's edges)."""
    def c3(xy, z):
        return [[round(float(xy[0]), 6), round(float(xy[1]), 6), round(float(z), 6)]]
    faces = [{"name": f"{name}_top", "corners": sum((c3(v, z1) for v in tri), [])},
             {"name": f"{name}_bottom", "corners": sum((c3(v, z0) for v in tri[::-1]), [])}]
    for k in range(3):
        a, b = tri[k], tri[(k + 1) % 3]
        faces.append({"name": f"{name}_side{k}",
                      "corners": c3(a, z0) + c3(b, z0) + c3(b, z1) + c3(a, z1)})
    return faces


def prism_target(rng: np.random.Generator, *, water_level: float = 0.0,
                 different_heights: bool = True, plinth: bool = False,
                 shift: float = 0.0, missing: bool = False, declare: bool = False,
                 blocks_per_side: int = 3) -> dict:
    """The patent's twin-block target with full prisms (module docstring, kind "prism").

    Each column: an above-water prism (heights 0.8-1.0 m) over a right triangle with legs
    drawn in 0.8-1.2 m (across) and 1.2-1.8 m (along the wall), and a below-water prism over
    the same triangle shifted along the column by *shift* (m), 1.0 m tall when
    *different_heights* (else as tall as the above-water one); the first north column sits
    0.25 m lower. *plinth*: each below-water prism stands on a slab 0.3 m wider; *missing*:
    one column has no below-water prism; *declare*: the below-water faces name their twin
    (``"twin"``; tops also ``"offset_m"``).
    """
    w = water_level
    half = float(rng.uniform(2.5, 3.5))
    depth, length = float(rng.uniform(0.8, 1.2)), float(rng.uniform(1.2, 1.8))
    gap = float(rng.uniform(0.8, 1.2))
    h_up = float(rng.uniform(0.8, 1.0))
    h_dn = 1.0 if different_heights else h_up
    floor = w - 4.0
    faces = [{"name": "wall", "corners": [[0.0, -half, floor], [0.0, half, floor],
                                          [0.0, half, w + 2.0], [0.0, -half, w + 2.0]]}]
    skip = int(rng.integers(0, 2 * blocks_per_side)) if missing else -1
    k_col = 0
    for side, s in (("N", 1.0), ("S", -1.0)):
        for k in range(blocks_per_side):
            y0 = s * (half + 0.3 + k * (length + gap))
            tri = np.array([[0.0, y0], [-depth, y0], [0.0, y0 + s * length]])
            if s < 0:
                tri = tri[[0, 2, 1]]       # keep the corner order counter-clockwise
            drop = 0.25 if (side == "N" and k == 0) else 0.0
            up0 = w + 0.4 - drop
            faces += _prism(f"{side}{k + 1}_up", tri, up0, up0 + h_up)
            if k_col != skip:
                dn1 = w - 1.3 - drop
                tri_dn = tri + np.array([0.0, s * shift])
                dn = _prism(f"{side}{k + 1}_dn", tri_dn, dn1 - h_dn, dn1)
                if declare:
                    for f in dn:
                        part = f["name"].rsplit("_", 1)[1]
                        if part != "bottom":
                            f["twin"] = f"{side}{k + 1}_up_{part}"
                        if part == "top":
                            f["offset_m"] = round(dn1 - (up0 + h_up), 6)
                faces += dn
                if plinth:
                    # A similar triangle 1.8× the size (parallel sides, a ring ~0.25 m wide
                    # round the block), flush with the wall.
                    c = tri_dn.mean(axis=0)
                    wide = c + 1.8 * (tri_dn - c)
                    wide[:, 0] -= wide[:, 0].max()
                    faces += _prism(f"{side}{k + 1}_plinth", wide, dn1 - h_dn - 0.3,
                                    dn1 - h_dn)
            k_col += 1
    return {"frame": "ENU", "water_level_m": float(w), "faces": faces}


def random_target(rng: np.random.Generator, kind: str | None = None) -> dict:
    """A target drawn at random: kind, number and size of blocks, spacing, which side's
    first block is lower and by how much, wall height, water level, twin heights/shift."""
    kind = kind or str(rng.choice(KINDS))
    water = float(rng.uniform(-0.4, 0.4))
    if kind == "prism":
        return prism_target(rng, water_level=water,
                            different_heights=bool(rng.random() < 0.8),
                            plinth=bool(rng.random() < 0.3),
                            shift=float(rng.choice([0.0, rng.uniform(-0.2, 0.2)])),
                            missing=bool(rng.random() < 0.2),
                            declare=bool(rng.random() < 0.2),
                            blocks_per_side=int(rng.integers(2, 4)))
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
