#!/usr/bin/env bash
# bench closures on a simulated loop: every candidate in closures.csv, labelled by the run's
# truth; the tables, the picture and the run's ATE written; a closure the graph kept is true; with
# --oracle only true closures go in.
#   bench_closures.sh SEMCHAIN WORLD WORK_DIR
set -euo pipefail
semchain="$1"
world="$2"
work="$3"
rm -rf "$work"
mkdir -p "$work"
cd "$work"

"$semchain" simulate --world "$world" --out run --seed 3 --no-frames >/dev/null
# Submaps and loops short enough for a small room's laps.
cat >loops.yaml <<'YAML'
pose_graph: {submap_travel_meters: 5.0, min_loop_travel_meters: 10.0}
YAML
"$semchain" bench closures --log run/log.clf --reference run/truth.txt --config loops.yaml \
  --particles 4 --seed 2 --out bench >/dev/null 2>&1

for file in closures.csv results.json results.md precision_recall.png trajectory.txt; do
  [ -s "bench/$file" ] || { echo "FAIL: bench/$file missing or empty"; exit 1; }
done
head -1 bench/closures.csv | grep -q '^from_node,to_node,from_scan,to_scan,' ||
  { echo "FAIL: closures.csv header"; head -1 bench/closures.csv; exit 1; }
rows=$(($(wc -l <bench/closures.csv) - 1))
[ "$rows" -ge 5 ] || { echo "FAIL: only $rows candidates"; exit 1; }
# The truth has a pose for every scan: no candidate is unlabelled.
if cut -d, -f19 bench/closures.csv | grep -q unlabelled; then
  echo "FAIL: an unlabelled candidate with a pose of truth for every scan"; exit 1
fi
# Every closure still in the graph at the end (column 16) is a true one (column 19).
awk -F, 'NR > 1 && $16 == 1 && $19 != "true" {bad++} END {exit bad > 0}' bench/closures.csv ||
  { echo "FAIL: a false closure in the graph"; grep ',1,[0-9.]*,[0-9.]*,false' bench/closures.csv; exit 1; }
kept=$(awk -F, 'NR > 1 && $16 == 1' bench/closures.csv | wc -l)
[ "$kept" -ge 1 ] || { echo "FAIL: no closure kept"; exit 1; }
grep -q '^| 0.65 | ' bench/results.md || { echo "FAIL: no 0.65 row"; cat bench/results.md; exit 1; }
grep -q '"ate_rmse_aligned_m"' bench/results.json || { echo "FAIL: no aligned ATE"; exit 1; }

# --oracle: the reference verifies, so every closure that went into the graph (column 14 added or
# confirmed) is a true one.
"$semchain" bench closures --log run/log.clf --reference run/truth.txt --config loops.yaml \
  --particles 4 --seed 2 --oracle --out oracle >/dev/null 2>&1
grep -q '"oracle_verification": true' oracle/results.json || { echo "FAIL: oracle not recorded"; exit 1; }
grep -q 'Oracle verification' oracle/results.md || { echo "FAIL: results.md does not say oracle"; exit 1; }
if grep -q 'Oracle verification' bench/results.md; then echo "FAIL: oracle said without it"; exit 1; fi
added=$(awk -F, 'NR > 1 && ($14 == "added" || $14 == "confirmed")' oracle/closures.csv | wc -l)
[ "$added" -ge 1 ] || { echo "FAIL: the oracle let no closure in"; exit 1; }
awk -F, 'NR > 1 && ($14 == "added" || $14 == "confirmed") && $19 != "true" {bad++} END {exit bad > 0}' \
  oracle/closures.csv || { echo "FAIL: the oracle let a false closure in"; exit 1; }

# One reference, exactly.
if "$semchain" bench closures --log run/log.clf --out none >/dev/null 2>err.txt; then
  echo "FAIL: no reference accepted"; exit 1
fi
grep -q "give exactly one of --relations, --reference, --perturb-odometry" err.txt ||
  { echo "FAIL: unclear error:"; cat err.txt; exit 1; }
echo "ok: $rows candidates, $kept kept"
