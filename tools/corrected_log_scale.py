#!/usr/bin/python3
"""How well the poses of a corrected CARMEN log agree with the scale of its own scans.

    /usr/bin/python3 tools/corrected_log_scale.py LOG [--gap K] [--every N]
    (numpy; LOG may be gzipped; FLASER or ROBOTLASER1 lines)

A corrected log's poses come from someone's SLAM, and a SLAM can stretch or shrink a map along
corridors where its scans say little. Scored against such poses, a SLAM run that follows the
scans exactly is off by the difference. This tool measures it: for scan pairs (i, i + K) of the
log, the relative pose the log gives is scaled by (1 + s) in translation, scan i + K is placed on
scan i there, and the point-to-line distance of every return to the other scan's surface
(normals from neighbouring returns; capped at 0.1 m) is averaged over all pairs. The s that fits
best is the scale the scans prefer relative to the poses: 0 when the poses are the scans' own
geometry, negative when the poses stretch it. Then it prints the ATE a trajectory at that scale
would have against the poses (scaled about the first pose, as `bench slam` starts at the true
first pose; and rigidly aligned), the floor for any SLAM that follows the scans.
"""

from __future__ import annotations

import argparse
import gzip
import math
import sys

import numpy as np


def read_log(path: str) -> tuple[list[np.ndarray], np.ndarray]:
    """Returns (laser-frame points) and poses of every FLASER or ROBOTLASER1 line. The pose is
    the line's own laser pose, or the TRUEPOS line before it where the log has them (the
    simulator's ground truth)."""
    opener = gzip.open if path.endswith(".gz") else open
    scans: list[np.ndarray] = []
    poses: list[list[float]] = []
    truth: list[float] | None = None
    with opener(path, "rt") as log:
        for number, line in enumerate(log, 1):
            fields = line.split()
            try:
                if fields and fields[0] == "TRUEPOS":
                    truth = [float(x) for x in fields[1:4]]
                elif fields and fields[0] == "FLASER":
                    count = int(fields[1])
                    ranges = np.array([float(x) for x in fields[2 : 2 + count]])
                    step = math.pi / (count - 1 if count % 2 == 1 else count)
                    scans.append(scan_points(ranges, -math.pi / 2, step))
                    poses.append(truth or [float(x) for x in fields[2 + count : 5 + count]])
                elif fields and fields[0] == "ROBOTLASER1":
                    start, step = float(fields[2]), float(fields[4])
                    count = int(fields[8])
                    ranges = np.array([float(x) for x in fields[9 : 9 + count]])
                    remissions = int(fields[9 + count])
                    pose_at = 10 + count + remissions
                    scans.append(scan_points(ranges, start, step))
                    poses.append(truth or [float(x) for x in fields[pose_at : pose_at + 3]])
            except (ValueError, IndexError):
                sys.exit(f"{path}:{number}: malformed {fields[0]} line")
    if len(scans) < 2:
        sys.exit(f"{path}: fewer than two laser lines")
    return scans, np.array(poses)


def scan_points(
    ranges: np.ndarray, start: float, step: float, max_range: float = 25.0
) -> np.ndarray:
    """Returns within max_range in the laser frame (the laser at the pose; the CARMEN logs of
    shared/data have no laser offset)."""
    angles = start + step * np.arange(len(ranges))
    keep = (ranges > 0.1) & (ranges < max_range)
    return np.stack([ranges[keep] * np.cos(angles[keep]), ranges[keep] * np.sin(angles[keep])], 1)


def surface_normals(points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Points whose two neighbours lie within 0.3 m, with the normal of the line through them."""
    before, after = points[:-2], points[2:]
    middle = points[1:-1]
    near = (np.linalg.norm(middle - before, axis=1) < 0.3) & (
        np.linalg.norm(after - middle, axis=1) < 0.3
    )
    tangent = after - before
    tangent /= np.maximum(np.linalg.norm(tangent, axis=1, keepdims=True), 1e-12)
    normals = np.stack([-tangent[:, 1], tangent[:, 0]], 1)
    return middle[near], normals[near]


def relative(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    c, s = math.cos(a[2]), math.sin(a[2])
    d = b[:2] - a[:2]
    return np.array([c * d[0] + s * d[1], -s * d[0] + c * d[1], b[2] - a[2]])


def place(pose: np.ndarray, points: np.ndarray) -> np.ndarray:
    c, s = math.cos(pose[2]), math.sin(pose[2])
    return points @ np.array([[c, s], [-s, c]]) + pose[:2]


def scale_costs(scans, poses, gap: int, every: int, scales: np.ndarray) -> tuple[np.ndarray, int]:
    total = np.zeros(len(scales))
    pairs = 0
    for i in range(0, len(scans) - gap, every):
        motion = relative(poses[i], poses[i + gap])
        if np.hypot(motion[0], motion[1]) < 1.0:
            continue
        surface, normals = surface_normals(scans[i])
        query = scans[i + gap]
        if len(surface) < 20 or len(query) < 20:
            continue
        for k, s in enumerate(scales):
            scaled = motion.copy()
            scaled[:2] *= 1.0 + s
            placed = place(scaled, query)
            d2 = ((placed[:, None, :] - surface[None, :, :]) ** 2).sum(-1)
            nearest = d2.argmin(1)
            residual = np.abs(((placed - surface[nearest]) * normals[nearest]).sum(1))
            total[k] += (np.minimum(residual, 0.1) ** 2).mean()
        pairs += 1
    return total / max(pairs, 1), pairs


def ate_at_scale(poses: np.ndarray, s: float) -> tuple[float, float]:
    truth = poses[:, :2]
    scaled = truth[0] + (truth - truth[0]) * (1.0 + s)
    plain = math.sqrt(((scaled - truth) ** 2).sum(1).mean())
    p = scaled - scaled.mean(0)
    q = truth - truth.mean(0)
    u, _, vt = np.linalg.svd(p.T @ q)
    rotation = (u @ vt).T
    aligned = math.sqrt((((rotation @ p.T).T - q) ** 2).sum(1).mean())
    return plain, aligned


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("log")
    parser.add_argument("--gap", type=int, default=5, help="pair scan i with scan i + GAP (5)")
    parser.add_argument("--every", type=int, default=3, help="take every N-th scan as i (3)")
    args = parser.parse_args()
    if args.gap < 1 or args.every < 1:
        sys.exit("--gap and --every must be positive")
    try:
        scans, poses = read_log(args.log)
    except (OSError, EOFError, UnicodeDecodeError) as error:
        sys.exit(f"{args.log}: cannot read: {error}")
    scales = np.linspace(-0.01, 0.01, 21)
    costs, pairs = scale_costs(scans, poses, args.gap, args.every, scales)
    if pairs == 0:
        sys.exit(f"{args.log}: no scan pairs at least 1 m apart")
    print(f"{pairs} scan pairs (i, i + {args.gap})")
    for s, cost in zip(scales, costs):
        print(f"  scale {s:+.3f}: mean squared point-to-line distance {cost:.6f} m^2")
    best = scales[int(costs.argmin())]
    plain, aligned = ate_at_scale(poses, best)
    print(f"best fit: the scans prefer the poses' translations scaled by {1 + best:.3f}")
    print(
        f"a trajectory at that scale: ATE {plain:.3f} m from the first pose, "
        f"{aligned:.3f} m aligned"
    )


if __name__ == "__main__":
    main()
