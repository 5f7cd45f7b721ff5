"""Design of the pool calibration target (seed 003, step 1) as a ``target.json`` dict.

Frame: target ENU, metres, origin at the target centre, Y (north) along the wall, X
(east) perpendicular to it, Z up. The wall face is the plane ``x = 0`` facing west
(``-x``), the side the vessel passes on with its starboard side to the target. Triangular
block columns stand on both sides (north ``N1, N2 ...`` beyond ``y = +wall_length/2``,
south ``S1, S2 ...`` beyond ``-wall_length/2``) at equal spacing, flush with the wall
plane and sticking out towards the vessel. Each block is a vertical prism whose
horizontal cross-section is a right triangle: one vertical face perpendicular to the wall
(normal along Y), one oblique vertical face (facing the vessel and the far end), top and
bottom horizontal faces. The first south block is lower than the first north block: its
top is below the water level (seen only by the multibeam) while the others cross the
water level (seen by the scanner above and by the multibeam below), which gives the
seed's Z step (4.2) its above/below-water horizontal pair of known height difference.
"""

from __future__ import annotations


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
    return faces


def build_target(
    *,
    wall_length: float = 6.0,
    wall_bottom: float = -4.5,
    wall_top: float = 2.0,
    blocks_per_side: int = 2,
    block_gap: float = 0.3,
    block_depth: float = 1.0,
    block_length: float = 1.5,
    block_spacing: float = 0.6,
    block_bottom: float = -4.5,
    block_top: float = 1.3,
    low_block_top: float = -3.0,
    water_level: float = 0.0,
) -> dict:
    """Return the ``target.json`` document of a seed-003 calibration target.

    Parameters
    ----------
    wall_length, wall_bottom, wall_top : float
        Wall face extent along Y (m) and its bottom/top heights (m, ENU up).
    blocks_per_side : int
        Number of triangular blocks in each column (north and south).
    block_gap : float
        Gap between the wall end and the first block, m.
    block_depth, block_length : float
        Plan-view legs of the right triangle: across (towards the vessel) and along Y, m.
    block_spacing : float
        Equal gap between successive blocks of one column, m.
    block_bottom, block_top : float
        Heights of the blocks' bottom and top faces, m (tops above water).
    low_block_top : float
        Top height of the first south block, which sits lower (below water), m.
    water_level : float
        Water level, m.
    """
    if not (wall_bottom < water_level < wall_top):
        raise ValueError("the wall must cross the water level")
    if not (block_bottom < water_level < block_top):
        raise ValueError("the blocks must cross the water level")
    if not (block_bottom < low_block_top < water_level):
        raise ValueError("the low block's top must be below water and above its bottom")
    half = wall_length / 2.0
    faces = [{"name": "wall", "corners": [[0.0, -half, wall_bottom], [0.0, half, wall_bottom],
                                          [0.0, half, wall_top], [0.0, -half, wall_top]]}]
    step = block_length + block_spacing
    for side, sign in (("N", 1.0), ("S", -1.0)):
        for k in range(blocks_per_side):
            y0 = sign * (half + block_gap + k * step)
            top = low_block_top if (side == "S" and k == 0) else block_top
            faces += _block(f"{side}{k + 1}", y0, sign, block_depth, block_length,
                            block_bottom, top)
    return {"frame": "ENU", "water_level_m": float(water_level), "faces": faces}
