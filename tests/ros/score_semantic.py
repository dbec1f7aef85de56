#!/usr/bin/python3
"""Scores a semantic.json against the objects of a world YAML, as the e2e tests do.

An object of the map matches the nearest unmatched world object of its class within 0.3 m
(tests/semantic_worlds_e2e_test.cc), the objects seen in most frames first; precision = matched /
map objects, recall = matched / world objects. Prints one JSON object; exits 1 below
--min-precision or --min-recall, 2 on a file it cannot read.

Each false map object and each missed world object also gets a reason, counted in "false_why"
and "missed_why", so that a score can be traced to the step that lost it:
- a false object is "mapped twice" (a world object of its class within its half diagonal, or
  0.3 m, is matched or claimed by a false object seen in more frames), "offset" (one lies within --near: the map placed it
  wrong), "wrong class" (an object of another class is within --near: the detections misnamed it) or "nothing
  near" (a detection of nothing real);
- a missed object is "offset" (a false map object of its class lies within --near), "wrong class"
  (a false map object of another class does) or "not mapped".
"""
import argparse
import json
import math
import sys
from typing import Any

import yaml

WorldObject = tuple[str, float, float, float]  # class, x, y, half diagonal


def world_objects(entries: list[dict[str, Any]]) -> list[WorldObject]:
    """The world YAML's objects; the half diagonal of a box's or a circle's footprint."""
    objects = []
    for o in entries:
        if "radius" in o:
            half_diagonal = math.sqrt(2.0) * float(o["radius"])
        else:
            half_diagonal = 0.5 * math.hypot(float(o.get("width", 0)), float(o.get("depth", 0)))
        objects.append((o["class"], float(o["x"]), float(o["y"]), half_diagonal))
    return objects


def nearest(cx: float, cy: float, world: list[WorldObject], accept) -> tuple[int, float]:
    """Index and distance of the nearest world object that 'accept(j, name)' allows."""
    best, best_d = -1, math.inf
    for j, (name, x, y, _) in enumerate(world):
        d = math.hypot(cx - x, cy - y)
        if accept(j, name) and d < best_d:
            best, best_d = j, d
    return best, best_d


def score(mapped: list[dict[str, Any]], world: list[WorldObject], max_distance: float,
          near: float) -> dict[str, Any]:
    order = sorted(range(len(mapped)), key=lambda i: -mapped[i].get("observations", 0))
    taken = [False] * len(world)
    match = [-1] * len(mapped)
    error = 0.0
    for i in order:
        cx, cy = mapped[i]["center"]
        name = mapped[i]["class"]
        best, best_d = nearest(cx, cy, world, lambda j, n: not taken[j] and n == name)
        if best >= 0 and best_d <= max_distance:
            taken[best] = True
            match[i] = best
            error += best_d

    # A world object is claimed by its match, or else by the false object of its class seen in
    # most frames that lies within its half diagonal.
    claimed = list(taken)
    false_objects = []
    for i in order:
        if match[i] >= 0:
            continue
        cx, cy = mapped[i]["center"]
        name = mapped[i]["class"]
        same, same_d = nearest(cx, cy, world, lambda j, n: n == name)
        other, other_d = nearest(cx, cy, world, lambda j, n: n != name)
        if same >= 0 and same_d <= max(max_distance, world[same][3]):
            why = "mapped twice" if claimed[same] else "offset"
            claimed[same] = True
        elif same >= 0 and same_d <= near:
            why = "offset"
        elif other >= 0 and other_d <= near:
            why = "wrong class"
        else:
            why = "nothing near"
        false_objects.append({"class": name, "center": [cx, cy], "why": why})

    missed = []
    for j, (name, x, y, _) in enumerate(world):
        if taken[j]:
            continue
        why = "not mapped"
        for obj in false_objects:
            if math.hypot(obj["center"][0] - x, obj["center"][1] - y) > near:
                continue
            if obj["class"] == name:
                why = "offset"
                break
            why = "wrong class"
        missed.append({"class": name, "center": [x, y], "why": why})

    matched = sum(1 for m in match if m >= 0)

    def count(objects: list[dict[str, Any]]) -> dict[str, int]:
        counts: dict[str, int] = {}
        for obj in objects:
            counts[obj["why"]] = counts.get(obj["why"], 0) + 1
        return counts

    return {"objects": len(mapped), "world_objects": len(world), "matched": matched,
            "precision": matched / len(mapped) if mapped else 0.0,
            "recall": matched / len(world) if world else 0.0,
            "mean_centre_error_m": error / matched if matched else None,
            "false_why": count(false_objects), "missed_why": count(missed),
            "unmatched_map_objects": false_objects, "missed_world_objects": missed}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("semantic_json")
    parser.add_argument("world_yaml")
    parser.add_argument("--max-distance", type=float, default=0.3,
                        help="a match's largest centre distance (metres, default 0.3)")
    parser.add_argument("--near", type=float, default=1.0,
                        help="how far a reason's object may lie (metres, default 1.0)")
    parser.add_argument("--min-precision", type=float, default=0.97)
    parser.add_argument("--min-recall", type=float, default=0.97)
    args = parser.parse_args()
    try:
        with open(args.semantic_json, encoding="utf-8") as file:
            mapped = json.load(file)["objects"]
        for i, obj in enumerate(mapped):
            if not isinstance(obj.get("class"), str) or len(obj.get("center") or []) != 2:
                raise ValueError(f"object {i} lacks a class or a two-number centre")
    except (OSError, ValueError, KeyError, TypeError, AttributeError) as error:
        print(f"{args.semantic_json}: not a semantic map ({error})", file=sys.stderr)
        return 2
    try:
        with open(args.world_yaml, encoding="utf-8") as file:
            world = world_objects(yaml.safe_load(file)["objects"])
    except (OSError, yaml.YAMLError, KeyError, TypeError, ValueError) as error:
        print(f"{args.world_yaml}: not a world with objects ({error})", file=sys.stderr)
        return 2
    result = score(mapped, world, args.max_distance, args.near)
    print(json.dumps(result, indent=2))
    ok = result["precision"] >= args.min_precision and result["recall"] >= args.min_recall
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
