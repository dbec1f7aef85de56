#!/usr/bin/python3
"""Scores a semantic.json against the objects of a world YAML, as the e2e tests do.

An object of the map matches the nearest unmatched world object of its class within 0.3 m
(tests/semantic_worlds_e2e_test.cc); precision = matched / map objects, recall = matched /
world objects. Prints one JSON object; exits 1 below --min-precision or --min-recall.
"""
import argparse
import json
import math
import sys

import yaml


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("semantic_json")
    parser.add_argument("world_yaml")
    parser.add_argument("--max-distance", type=float, default=0.3)
    parser.add_argument("--min-precision", type=float, default=0.97)
    parser.add_argument("--min-recall", type=float, default=0.97)
    args = parser.parse_args()
    with open(args.semantic_json, encoding="utf-8") as file:
        mapped = json.load(file)["objects"]
    with open(args.world_yaml, encoding="utf-8") as file:
        world = [(o["class"], float(o["x"]), float(o["y"])) for o in yaml.safe_load(file)["objects"]]
    taken = [False] * len(world)
    matched, error, misses = 0, 0.0, []
    for obj in mapped:
        cx, cy = obj["center"]
        best, best_d = -1, math.inf
        for j, (name, x, y) in enumerate(world):
            d = math.hypot(cx - x, cy - y)
            if not taken[j] and name == obj["class"] and d <= args.max_distance and d < best_d:
                best, best_d = j, d
        if best < 0:
            misses.append({"class": obj["class"], "center": [cx, cy]})
            continue
        taken[best] = True
        matched += 1
        error += best_d
    precision = matched / len(mapped) if mapped else 0.0
    recall = matched / len(world) if world else 0.0
    result = {"objects": len(mapped), "world_objects": len(world), "matched": matched,
              "precision": precision, "recall": recall,
              "mean_centre_error_m": error / matched if matched else None,
              "unmatched_map_objects": misses,
              "missed_world_objects": [list(w) for w, t in zip(world, taken) if not t]}
    print(json.dumps(result, indent=2))
    return 0 if precision >= args.min_precision and recall >= args.min_recall else 1


if __name__ == "__main__":
    sys.exit(main())
