#!/usr/bin/python3
"""Checks the node's /amcl_pose publishing against what a checker received.

check_pose_counts.py RESULT.json STATS.json: RESULT is node_checker.py's output (poses: the
/amcl_pose messages it received), STATS the node's ~stats_file. The checker must have received
every pose the node published. As amcl, the node publishes on filter updates only (after the robot
moved update_min_d or turned update_min_a), so fewer poses than scans with a pose; with
~publish_pose_every_scan one after every scan with a pose. Exits 1 when not.
"""
import json
import sys


def main() -> int:
    with open(sys.argv[1], encoding="utf-8") as file:
        result = json.load(file)
    with open(sys.argv[2], encoding="utf-8") as file:
        stats = json.load(file)
    received, published = result["poses"], stats["poses_published"]
    with_pose, every_scan = stats["scans_with_pose"], stats["publish_pose_every_scan"]
    problems = []
    if received != published:
        problems.append(f"the checker received {received} poses, the node published {published}")
    if every_scan and published != with_pose:
        problems.append(f"publish_pose_every_scan: {published} poses for {with_pose} scans")
    if not every_scan and not 0 < published < with_pose:
        problems.append(f"on filter updates: {published} poses for {with_pose} scans")
    mode = "after every scan" if every_scan else "on filter updates"
    print(f"/amcl_pose {mode}: {published} published for {with_pose} scans with a pose, "
          f"{received} received")
    for problem in problems:
        print(f"FAIL: {problem}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
