#!/usr/bin/env bash
# bench track on a simulated loop: the map from SLAM on the log, then AMCL with and without scan
# tracking from the first pose; every scan scored against the map's trajectory; the tables, the
# trace and the pictures written; scan tracking keeps every scan within the target on clean
# simulated scans and is no worse than the filter alone.
#   bench_track.sh SEMCHAIN WORLD WORK_DIR
set -euo pipefail
semchain="$1"
world="$2"
work="$3"
rm -rf "$work"
mkdir -p "$work"
cd "$work"

"$semchain" simulate --world "$world" --out run --seed 3 --no-frames >/dev/null
"$semchain" bench track --log run/log.clf --methods amcl --particles 500 --out matched \
  >/dev/null 2>&1
# The filter alone, on the map just built (no second SLAM run).
"$semchain" bench track --log run/log.clf --map matched/map --methods amcl --particles 500 \
  --no-scan-tracking --out alone >/dev/null 2>&1

for file in results.json results.md trace.csv error_amcl.png map/map.yaml map/trajectory.txt; do
  [ -s "matched/$file" ] || { echo "FAIL: matched/$file missing or empty"; exit 1; }
done
scans=$(grep -cE '^(ROBOTLASER1|FLASER) ' run/log.clf)
rows=$(($(wc -l <matched/trace.csv) - 1))
[ "$rows" -eq "$scans" ] || { echo "FAIL: $rows trace rows for $scans scans"; exit 1; }

/usr/bin/python3 - matched/results.json alone/results.json <<'PY'
import json, sys
matched = json.load(open(sys.argv[1]))["methods"]["amcl"]
alone = json.load(open(sys.argv[2]))["methods"]["amcl"]
assert matched["estimated"] == matched["scans"], matched
assert matched["scan_matched"] >= 0.95 * matched["scans"], matched
assert matched["within_target"], matched
assert matched["over_target"]["scans"] == 0, matched
assert alone["scan_matched"] == 0, alone
assert matched["median_m"] <= alone["median_m"] and matched["max_m"] <= alone["max_m"], (matched, alone)
print("ok: median %.3f m / %.2f deg, max %.3f m / %.2f deg (filter alone: median %.3f m, max %.3f m)"
      % (matched["median_m"], matched["median_deg"], matched["max_m"], matched["max_deg"],
         alone["median_m"], alone["max_m"]))
PY

# A map folder without a trajectory is one clear error.
mkdir -p empty_map
if "$semchain" bench track --log run/log.clf --map empty_map --out none >/dev/null 2>err.txt; then
  echo "FAIL: a map without trajectory.txt accepted"; exit 1
fi
grep -q "empty_map" err.txt || { echo "FAIL: the error does not name the map folder:"; cat err.txt; exit 1; }
