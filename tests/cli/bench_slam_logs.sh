#!/usr/bin/env bash
# bench slam over several logs, configurations and seeds: one run per cell, a summary row per
# (log, configuration, particles, variant) over the seeds, and accurate SLAM on a simulated log.
#   bench_slam_logs.sh SEMCHAIN WORLD CONFIG WORK_DIR
set -euo pipefail
semchain="$1"
world="$2"
config="$3"
work="$4"
rm -rf "$work"
mkdir -p "$work"
cd "$work"

"$semchain" simulate --world "$world" --out run --seed 3 --no-frames >/dev/null
# Relations from the truth: every 10th scan to the one 10 later, in the first one's frame.
awk '!/^#/ {n++; t[n]=$1; x[n]=$2; y[n]=$3; th[n]=$4}
  END {for (i = 1; i + 10 <= n; i += 10) {j = i + 10; dx = x[j] - x[i]; dy = y[j] - y[i];
       c = cos(th[i]); s = sin(th[i]); d = th[j] - th[i];
       printf "%.6f %.6f %.6f %.6f 0 0 0 %.6f\n", t[i], t[j], c*dx + s*dy, -s*dx + c*dy,
              atan2(sin(d), cos(d))}}' run/truth.txt >run.relations
cp run/log.clf corridor_a.clf
cp run/log.clf corridor_b.clf

if "$semchain" bench slam --log corridor_a.clf,corridor_b.clf --relations run.relations \
  --out mismatch >/dev/null 2>err.txt; then
  echo "FAIL: two logs with one relations file were accepted"
  exit 1
fi
grep -q "2 logs but 1 relation files" err.txt || { echo "FAIL: unclear error:"; cat err.txt; exit 1; }

"$semchain" bench slam --log corridor_a.clf,corridor_b.clf \
  --relations run.relations,run.relations --config default,"$config" --particles 2 \
  --variants plain --seed 4,7 --max-scans 300 --out bench >/dev/null 2>&1

runs=$(grep -c '"seed": [47],' bench/results.json)
[ "$runs" -eq 8 ] || { echo "FAIL: $runs runs, expected 2 logs x 2 configs x 2 seeds = 8"; exit 1; }
for log in corridor_a corridor_b; do
  for cfg in default "$(basename "$config" .yaml)"; do
    grep -q "^| $log | $cfg | 2 | plain | 2 | " bench/results.md ||
      { echo "FAIL: no summary row for $log / $cfg over 2 seeds"; cat bench/results.md; exit 1; }
  done
done
# Each run reports the filter's recovery searches (steps where no particle's match was trusted).
recoveries=$(grep -c '"recoveries": [0-9]' bench/results.json)
[ "$recoveries" -eq 8 ] || { echo "FAIL: $recoveries of 8 runs report recoveries"; exit 1; }
# The default configuration maps the corridor to within a few centimetres (mean over seeds).
mean=$(grep "^| corridor_a | default | 2 | plain | 2 | " bench/results.md | cut -d'|' -f7 |
  awk '{print $1}')
awk -v m="$mean" 'BEGIN {exit !(m < 0.05)}' ||
  { echo "FAIL: mean relation error $mean m on the simulated corridor"; exit 1; }
echo "ok: bench slam over 2 logs x 2 configs x 2 seeds (default: $mean m)"
