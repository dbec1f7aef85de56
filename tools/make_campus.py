#!/usr/bin/python3
"""Writes worlds/campus.yaml, the simulated campus (SLAM with loops of hundreds of metres).

    python3 tools/make_campus.py [OUT.yaml]   (standard library only; default worlds/campus.yaml
                                                beside this tool)

The campus is a ring of corridors around two buildings, like the figure 日: a 92 m x 52 m outline,
corridors 2.4 m wide along its four sides and one across its middle (y 24.8-27.2), so that two
loops of 229 m (corridor centre lines) share the middle corridor. Walls are not bare: along every
straight wall, niches (door recesses) 1.0-1.6 m wide and 0.3-0.6 m deep sit at irregular spacing
(3-9 m, drawn from a fixed seed), as in a real building; a long corridor with evenly spaced
features would let a scan matcher slide by one spacing. About half the niches hold a closed door,
some walls a clock above the laser's plane, so the camera has objects to see.

The robot is a real robot's: a 180-degree laser of 181 beams and 30 m range at 10 Hz (the CARMEN
logs' SICK), wheel odometry with noise and a systematic error (distance over-read by 1.5 %, turns
under-read by 1 %), so dead reckoning is metres off after one loop.

The mapping route: the south building's loop anticlockwise from (20, 1.2), through its start
(first loop closure after 229 m) on to (45, 1.2), back west to the south-west corner, north through the west corridor
to the north building's loop, around it anticlockwise and back along the middle corridor to the
west side (second loop closure: the middle corridor was mapped on the first loop), then down the
west corridor and east to the start. About 600 m.
"""

from __future__ import annotations

import math
import random
import sys
from pathlib import Path

WIDTH = 92.0  # the outline, x
HEIGHT = 52.0  # the outline, y
CORRIDOR = 2.4
SEED = 27  # niche positions and sizes

NICHE_SPACING = (3.0, 9.0)  # gap between niches along a wall (m)
NICHE_WIDTH = (1.0, 1.6)
NICHE_DEPTH = (0.3, 0.6)
CORNER_CLEARANCE = 3.0  # no niche this close to a wall's ends (corners stay clean)
DOOR_PROBABILITY = 0.5  # a niche holds a closed door
CLOCK_PROBABILITY = 0.15  # a clock hangs on the wall between two niches

Point = tuple[float, float]


def niched_wall(start: Point, end: Point, into: Point, rng: random.Random,
                objects: list[str]) -> list[Point]:
    """The polyline of a straight wall from start to end with niches recessed along 'into' (a unit
    vector pointing away from the corridor); appends the niches' doors and the wall's clocks."""
    length = math.dist(start, end)
    ux, uy = (end[0] - start[0]) / length, (end[1] - start[1]) / length
    # An object's back (its +y) against the wall: +y = (-sin yaw, cos yaw) = 'into'.
    yaw = math.atan2(-into[0], into[1])

    def at(s: float, depth: float = 0.0) -> Point:
        return (round(start[0] + ux * s + into[0] * depth, 3),
                round(start[1] + uy * s + into[1] * depth, 3))

    points = [at(0.0)]
    s = CORNER_CLEARANCE + rng.uniform(0.0, NICHE_SPACING[1] - NICHE_SPACING[0])
    while True:
        width = rng.uniform(*NICHE_WIDTH)
        depth = rng.uniform(*NICHE_DEPTH)
        if s + width > length - CORNER_CLEARANCE:
            break
        points += [at(s), at(s, depth), at(s + width, depth), at(s + width)]
        if rng.random() < DOOR_PROBABILITY:
            x, y = at(s + width / 2, depth)
            objects.append(f"  - {{class: door, x: {x}, y: {y}, yaw: {yaw:.7f}, "
                           f"width: {width - 0.1:.2f}, depth: 0.05, height: 2.05}}")
        gap = rng.uniform(*NICHE_SPACING)
        if rng.random() < CLOCK_PROBABILITY and gap > 1.0:
            x, y = at(s + width + gap / 2, -0.027)  # on the wall's corridor side
            objects.append(f"  - {{class: clock, x: {x}, y: {y}, yaw: {yaw:.7f}, "
                           f"width: 0.35, depth: 0.05, height: 0.35, base_height: 1.7}}")
        s += width + gap
    points.append(at(length))
    return points


def rectangle_walls(x0: float, y0: float, x1: float, y1: float, outward: bool,
                    rng: random.Random, objects: list[str]) -> list[list[Point]]:
    """The four sides of a rectangle, niches recessed outwards (the outline, whose corridor is
    inside) or inwards (a building, whose corridors are outside)."""
    sign = 1.0 if outward else -1.0
    corners = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]
    normals = [(0.0, -sign), (sign, 0.0), (0.0, sign), (-sign, 0.0)]  # south, east, north, west
    return [niched_wall(corners[i], corners[(i + 1) % 4], normals[i], rng, objects)
            for i in range(4)]


def main() -> None:
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else \
        Path(__file__).resolve().parent.parent / "worlds" / "campus.yaml"
    rng = random.Random(SEED)
    objects: list[str] = []
    mid_low = HEIGHT / 2 - CORRIDOR / 2
    mid_high = HEIGHT / 2 + CORRIDOR / 2
    walls = rectangle_walls(0.0, 0.0, WIDTH, HEIGHT, True, rng, objects)
    walls += rectangle_walls(CORRIDOR, CORRIDOR, WIDTH - CORRIDOR, mid_low, False, rng, objects)
    walls += rectangle_walls(CORRIDOR, mid_high, WIDTH - CORRIDOR, HEIGHT - CORRIDOR, False, rng,
                             objects)

    west, east = CORRIDOR / 2, WIDTH - CORRIDOR / 2
    south, middle, north = CORRIDOR / 2, HEIGHT / 2, HEIGHT - CORRIDOR / 2
    start = (20.0, south)
    # Loop closures happen where the robot drives through a place it mapped before; the first
    # loop therefore runs on 25 m past its start before turning back.
    through = (start[0] + 25.0, south)
    route = [start, (east, south), (east, middle), (west, middle), (west, south), through,
             (west, south), (west, middle), (west, north), (east, north), (east, middle),
             (west, middle), (west, south), start]

    lines = [
        "# The simulated campus: two loops of 229 m around two buildings (the figure",
        "# 日, 92 m x 52 m, corridors 2.4 m wide), niches at irregular spacing along every wall, a",
        "# SICK-like 180-degree laser of 30 m and wheel odometry with a systematic error. The mapping",
        "# route closes the south loop after 229 m, then the north loop (about 600 m in all).",
        "# Generated by tools/make_campus.py: edit the generator, not this file.",
        "",
        "name: campus",
        f"seed: {SEED}",
        "walls:",
    ]
    for wall in walls:
        lines.append("  - [" + ", ".join(f"[{x:g}, {y:g}]" for x, y in wall) + "]")
    lines += ["wall_height: 2.6", "wall_thickness: 0.05", "objects:"]
    lines += objects
    lines += [
        "robot:",
        f"  start: [{start[0]:g}, {start[1]:g}, 0]",
        "  radius: 0.25",
        "  lidar: {height: 0.3, beams: 181, fov_deg: 180, max_range: 30.0, noise_std: 0.01}",
        "  odometry_noise: [0.05, 0.002, 0.02, 0.01]",
        "  odometry_scale_error: [0.015, -0.01]",
        "  max_speed: 0.6",
        "  scan_rate_hz: 10",
        "  frame_rate_hz: 1",
        "mapping_route:",
    ]
    lines += [f"  - [{x:g}, {y:g}]" for x, y in route]
    x0, x1 = start[0] - 6.0, start[0] + 6.0
    lines.append(f"trial_region: [[{x0:g}, 0.2], [{x1:g}, 0.2], [{x1:g}, 2.2], [{x0:g}, 2.2]]"
                 "  # the south corridor around the start")
    out.write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
