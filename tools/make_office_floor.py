#!/usr/bin/python3
"""Writes worlds/office_floor.yaml, the look-alike office floor (relocalization at building scale).

    python3 tools/make_office_floor.py [OUT.yaml]   (standard library only; default
                                                      worlds/office_floor.yaml beside this tool)

The floor is 36 m x 14 m: a 2 m wide corridor (y 6-8) runs east-west through it, and six offices
of 6 m x 6 m open onto it on each side (south row S0-S5, y 0-6; north row N0-N5, y 8-14; index =
x // 6). Every office is one and the same office in its own frame -- origin at the middle of its
1 m doorway on the corridor wall, x along that wall, y into the office -- placed by a rigid
motion: the north offices by a translation, the south ones turned by 180 degrees as well (so the
doorways alternate along the corridor: north at x = 6i + 1.5, south at x = 6i + 4.5, each 1.5 m
from an office's side wall). Walls, the open door leaf and every furniture footprint (position,
size, yaw relative to the doorway) are therefore exactly the same in all twelve offices; only the
classes in the six variable slots differ, chosen so that no two offices agree in more than
MAX_SHARED of them (some offices share two objects' classes). The script writes the YAML so that
the repetition is exact; edit the tables below, never the YAML by hand.
"""

from __future__ import annotations

import math
import random
import sys
from dataclasses import dataclass
from pathlib import Path

OFFICE = 6.0  # office width along the corridor and depth (m)
CORRIDOR_Y = (6.0, 8.0)  # the corridor's walls
FLOOR_X = 36.0
FLOOR_Y = 14.0
DOORWAY = 1.0  # doorway width (m)
DOOR_FROM_SIDE = 1.5  # doorway centre to the office's near side wall (m)
ROWS = 6  # offices per side
TRIAL_OFFICE = "S2"  # the trial region: an office in the middle of the floor
MAX_SHARED = 2  # variable slots in which two offices may have the same class

PI = math.pi


@dataclass(frozen=True)
class Slot:
    """A furniture footprint in the office frame (x along the corridor wall, y into the room)."""

    name: str
    x: float
    y: float
    yaw: float  # the object's +y (its back) points at the wall it stands against
    classes: tuple[str, ...]  # one class: the same in every office
    width: float = 0.0
    depth: float = 0.0
    radius: float = 0.0
    base_height: float = 0.0


# The office, x from -1.5 (near side wall) to 4.5 (far side wall), y from 0 (corridor wall) to 6.
# The far- and near-wall pieces sit at different y: back to back across a side wall, two of the
# same class would merge into one object in the semantic map (its closing bridges the wall).
SLOTS: tuple[Slot, ...] = (
    # The door leaf, open 90 degrees into the room, hinged at the doorway's near edge.
    Slot("door", -0.55, 0.46, PI / 2, ("door",), width=0.9, depth=0.05),
    Slot("desk", 0.0, 5.6, 0.0, ("table",), width=1.4, depth=0.7),
    # On the desk, near its back edge (above the lidar: only the camera sees it).
    Slot("on desk", 0.0, 5.75, 0.0, ("computer", "clock"), width=0.45, depth=0.15,
         base_height=0.75),
    Slot("seat", 0.0, 4.75, PI, ("chair", "stool", "bucket", "cabinet"), width=0.5, depth=0.5),
    Slot("corner", 4.2, 5.7, 0.0, ("bucket", "stool", "cabinet", "chair"), width=0.45,
         depth=0.45),
    Slot("far wall", 4.0, 1.6, -PI / 2, ("sofa", "table", "cabinet"), width=1.8, depth=0.9),
    Slot("near wall", -0.45, 3.5, PI / 2, ("bed", "table", "sofa"), width=1.0, depth=2.0),
    Slot("by the door", 2.5, 0.3, PI, ("cabinet", "chair", "stool", "bucket"), width=0.5,
         depth=0.5),
)

# Height (and, for the clock, how far above its base the disc sits) by class.
HEIGHT = {"door": 2.05, "table": 0.75, "computer": 0.42, "clock": 0.32, "chair": 0.9,
          "stool": 0.5, "bucket": 0.4, "cabinet": 0.9, "sofa": 0.85, "bed": 0.95}

# The office tour in the office frame: in from the corridor's middle (y = -1), along the
# corridor wall (the camera looks at the far wall), up the room (desk, seat, corner), west (the
# near wall), back down (the object by the door) and out. Every point is >= 0.5 m from a surface.
TOUR: tuple[tuple[float, float], ...] = (
    (0.0, -1.0), (0.0, 1.2), (1.8, 1.2), (1.8, 4.0), (1.1, 4.0), (1.1, 1.2), (0.0, 1.2),
    (0.0, -1.0))


@dataclass(frozen=True)
class Office:
    name: str  # S0..S5, N0..N5
    door_x: float  # world x of the doorway's middle
    south: bool

    def to_world(self, x: float, y: float) -> tuple[float, float]:
        if self.south:  # turned by 180 degrees: x along -x, y along -y
            return self.door_x - x, CORRIDOR_Y[0] - y
        return self.door_x + x, CORRIDOR_Y[1] + y

    def yaw(self, yaw: float) -> float:
        return normalize(yaw + (PI if self.south else 0.0))


def normalize(angle: float) -> float:
    while angle > PI + 1e-9:
        angle -= 2 * PI
    while angle <= -PI + 1e-9:
        angle += 2 * PI
    return angle


def offices() -> list[Office]:
    """The twelve offices in the order the mapping route visits them (doorways west to east)."""
    result = []
    for i in range(ROWS):
        result.append(Office(f"N{i}", OFFICE * i + DOOR_FROM_SIDE, south=False))
        result.append(Office(f"S{i}", OFFICE * i + OFFICE - DOOR_FROM_SIDE, south=True))
    return result


def class_codes(count: int) -> list[tuple[str, ...]]:
    """'count' class tuples over the variable slots, pairwise agreeing in <= MAX_SHARED slots.

    Greedy picks from the candidates in a seeded random order, restarted with the next seed
    until 'count' are found (deterministic: the same tuples on every run).
    """
    variable = [s for s in SLOTS if len(s.classes) > 1]
    candidates: list[tuple[str, ...]] = [()]
    for slot in variable:
        candidates = [c + (k,) for c in candidates for k in slot.classes]

    def agree(a: tuple[str, ...], b: tuple[str, ...]) -> int:
        return sum(1 for p, q in zip(a, b) if p == q)

    for seed in range(10000):
        order = candidates[:]
        random.Random(seed).shuffle(order)
        chosen: list[tuple[str, ...]] = []
        for c in order:
            if all(agree(c, o) <= MAX_SHARED for o in chosen):
                chosen.append(c)
                if len(chosen) == count:
                    return chosen
    raise SystemExit(f"no {count} class tuples agree in <= {MAX_SHARED} slots")


def fmt(value: float) -> str:
    text = f"{value:.7f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def yaw_text(yaw: float) -> str:
    return fmt(round(yaw, 7))


def walls() -> list[str]:
    lines = [f"  - [[0, 0], [{fmt(FLOOR_X)}, 0], [{fmt(FLOOR_X)}, {fmt(FLOOR_Y)}], "
             f"[0, {fmt(FLOOR_Y)}], [0, 0]]  # the floor's outline"]
    for y, south in ((CORRIDOR_Y[0], True), (CORRIDOR_Y[1], False)):
        gaps = [o.door_x for o in offices() if o.south == south]
        x = 0.0
        side = "south" if south else "north"
        for k, g in enumerate(gaps):
            lines.append(f"  - [[{fmt(x)}, {fmt(y)}], [{fmt(g - DOORWAY / 2)}, {fmt(y)}]]"
                         + (f"  # corridor, {side} side, doorways 1 m wide" if k == 0 else ""))
            x = g + DOORWAY / 2
        lines.append(f"  - [[{fmt(x)}, {fmt(y)}], [{fmt(FLOOR_X)}, {fmt(y)}]]")
    for k in range(1, ROWS):
        x = fmt(OFFICE * k)
        lines.append(f"  - [[{x}, 0], [{x}, {fmt(CORRIDOR_Y[0])}]]"
                     + ("  # between the offices" if k == 1 else ""))
        lines.append(f"  - [[{x}, {fmt(CORRIDOR_Y[1])}], [{x}, {fmt(FLOOR_Y)}]]")
    return lines


def object_line(office: Office, slot: Slot, cls: str) -> str:
    x, y = office.to_world(slot.x, slot.y)
    fields = [f"class: {cls}", f"x: {fmt(round(x, 4))}", f"y: {fmt(round(y, 4))}"]
    if slot.radius > 0:
        fields.append(f"radius: {fmt(slot.radius)}")
    else:
        fields += [f"yaw: {yaw_text(office.yaw(slot.yaw))}", f"width: {fmt(slot.width)}",
                   f"depth: {fmt(slot.depth)}"]
    fields.append(f"height: {fmt(HEIGHT[cls])}")
    if slot.base_height > 0:
        fields.append(f"base_height: {fmt(slot.base_height)}")
    return "  - {" + ", ".join(fields) + "}"


def trial_region(office: Office) -> list[tuple[float, float]]:
    """The office less a 0.3 m band along its walls, counter-clockwise from the south-west."""
    inset = 0.3
    corners = [office.to_world(x, y) for x, y in
               ((-DOOR_FROM_SIDE + inset, inset), (OFFICE - DOOR_FROM_SIDE - inset, OFFICE - inset))]
    (x0, x1), (y0, y1) = sorted(p[0] for p in corners), sorted(p[1] for p in corners)
    return [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]


HEADER = """\
# A floor of twelve look-alike offices off one corridor (relocalization at building
# scale). 36 m x 14 m: a 2 m corridor (y 6-8) with six 6 m x 6 m offices on each side (south row
# S0-S5, y 0-6, and north row N0-N5, y 8-14, office i spanning x 6i to 6i + 6). Every office is
# the same office moved rigidly (the south ones also turned by 180 degrees): a 1 m doorway 1.5 m
# from one side wall (north doorways at x = 6i + 1.5, south at 6i + 4.5), its door leaf open
# against the doorway's near edge, a desk (table) at the back wall, and six variable slots --
# something on the desk (computer or clock), a seat in front of the desk, a small piece in the
# back corner, a large piece on the far side wall, a bed-sized piece on the near side wall and a
# small piece beside the door. Walls and footprints (position, size, yaw from the doorway) repeat
# exactly; only the classes differ, no two offices agreeing in more than two slots. So the laser
# cannot tell the offices apart and one pair of objects seldom can. A door closes each end of the
# corridor; a clock hangs on the east end wall. All ten classes of seed 000, built of parts.
# The mapping route drives the corridor eastwards, entering every office on a short tour that
# brings each object into the forward camera's view, and returns along the corridor to its start
# (a loop closure). The trial region is office S2 (x 12-18, south side), in the middle.
# Generated by tools/make_office_floor.py: edit the generator, not this file.
"""

ROBOT = """\
robot:
  start: [0.8, 7.0, 0.0]
  radius: 0.2
  # 359 beams 1 degree apart, centred on the heading (see two_similar_rooms.yaml).
  lidar: {height: 0.19, beams: 359, fov_deg: 358, max_range: 12.0, noise_std: 0.01}
  camera: {height: 0.5, fov_deg: 60, width: 320, height_px: 240, max_range: 6.0}
  odometry_noise: [0.01, 0.002, 0.01, 0.005]
  max_speed: 0.4
  max_turn_rate: 0.8
  scan_rate_hz: 10
  frame_rate_hz: 5
"""


def world_yaml() -> str:
    floor = offices()
    codes = class_codes(len(floor))
    # The trial office gets the code with the most distinct classes (besides the constant
    # door and desk); the others follow the route's order.
    fixed = {s.classes[0] for s in SLOTS if len(s.classes) == 1}
    codes.sort(key=lambda c: -len(set(c) - fixed))
    order = sorted(floor, key=lambda o: (o.name != TRIAL_OFFICE, floor.index(o)))
    assigned = {o.name: codes[i] for i, o in enumerate(order)}
    out = [HEADER, "name: office_floor", "seed: 22", "walls:"]
    out += walls()
    out += ["wall_height: 2.6", "wall_thickness: 0.05  # walls are seen from both sides",
            "objects:"]
    mid = fmt((CORRIDOR_Y[0] + CORRIDOR_Y[1]) / 2)
    out.append("  # The corridor's ends.")
    out.append(f"  - {{class: door, x: 0, y: {mid}, yaw: {yaw_text(PI / 2)}, width: 0.9, "
               f"depth: 0.1, height: 2.05}}")
    out.append(f"  - {{class: door, x: {fmt(FLOOR_X)}, y: {mid}, yaw: {yaw_text(PI / 2)}, "
               f"width: 0.9, depth: 0.1, height: 2.05}}")
    out.append(f"  - {{class: clock, x: {fmt(FLOOR_X - 0.027)}, y: {fmt(7.75)}, "
               f"yaw: {yaw_text(-PI / 2)}, width: 0.35, depth: 0.05, height: 0.35, "
               f"base_height: 1.7}}")
    for office in floor:
        code = iter(assigned[office.name])
        classes = [s.classes[0] if len(s.classes) == 1 else next(code) for s in SLOTS]
        x0 = min(office.to_world(-DOOR_FROM_SIDE, 0)[0], office.to_world(OFFICE - DOOR_FROM_SIDE,
                                                                         0)[0])
        side = "south" if office.south else "north"
        out.append(f"  # Office {office.name} ({side}, x {fmt(x0)}-{fmt(x0 + OFFICE)}): "
                   + ", ".join(classes[2:]) + ".")
        for slot, cls in zip(SLOTS, classes):
            out.append(object_line(office, slot, cls))
    out.append(ROBOT.rstrip("\n"))
    out.append("mapping_route:")
    out.append("  - [0.8, 7.0]")
    for office in floor:
        for k, (x, y) in enumerate(TOUR):
            wx, wy = office.to_world(x, y)
            note = f"   # office {office.name}" if k == 1 else ""
            out.append(f"  - [{fmt(round(wx, 4))}, {fmt(round(wy, 4))}]{note}")
    out.append("  - [0.8, 7.0]   # back along the corridor to the start")
    region = trial_region(next(o for o in floor if o.name == TRIAL_OFFICE))
    out.append("trial_region: [" + ", ".join(f"[{fmt(round(x, 4))}, {fmt(round(y, 4))}]"
                                             for x, y in region) + f"]  # office {TRIAL_OFFICE}")
    return "\n".join(out) + "\n"


def main(argv: list[str]) -> int:
    target = Path(argv[1]) if len(argv) > 1 else (
        Path(__file__).resolve().parent.parent / "worlds" / "office_floor.yaml")
    target.write_text(world_yaml())
    print(f"wrote {target}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
