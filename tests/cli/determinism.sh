#!/usr/bin/env bash
# Determinism: the same seed gives byte-identical outputs of simulate, slam (at 1 and 2 threads),
# semantic and bench reloc (its results without CPU readings, also with kept and reused runs).
#   determinism.sh SEMCHAIN WORLD WORK_DIR
set -euo pipefail
semchain="$1"
world="$2"
work="$3"
rm -rf "$work"
mkdir -p "$work"
cd "$work"

same() {  # same NAME DIR_A DIR_B FILE...
  local name="$1" a="$2" b="$3"
  shift 3
  for file in "$@"; do
    if ! cmp -s "$a/$file" "$b/$file"; then
      echo "FAIL: $name: $file differs between $a and $b"
      exit 1
    fi
  done
  echo "ok: $name"
}

"$semchain" simulate --world "$world" --out run_a --seed 9 >/dev/null
"$semchain" simulate --world "$world" --out run_b --seed 9 >/dev/null
if ! diff -r run_a run_b >/dev/null; then
  echo "FAIL: simulate: two runs with seed 9 differ"
  exit 1
fi
echo "ok: simulate"
"$semchain" slam --log run_a/log.clf --out map_1 --threads 1 >/dev/null 2>&1
"$semchain" slam --log run_a/log.clf --out map_2 --threads 2 >/dev/null 2>&1
same "slam 1 vs 2 threads" map_1 map_2 map.pgm map.yaml trajectory.txt
"$semchain" semantic --run run_a --map map_1 --out map_1 >/dev/null
"$semchain" semantic --run run_a --map map_2 --out map_2 >/dev/null
same semantic map_1 map_2 semantic.json keyframes.json semantic.png

# bench reloc: the same trials, outcomes, errors and times (CPU readings aside).
for run in a b; do
  "$semchain" bench reloc --world "$world" --trials 3 --seed 4 \
    --methods semantic-amcl,semantic-scanmatch --out "reloc_$run" >/dev/null 2>&1
  grep -v -E '"[a-z_]*cpu[a-z_]*_ms"' "reloc_$run/results.json" >"reloc_$run.json"
done
if ! cmp -s reloc_a.json reloc_b.json; then
  echo "FAIL: bench reloc: two runs with seed 4 differ beyond their CPU readings"
  diff reloc_a.json reloc_b.json | head -20
  exit 1
fi
echo "ok: bench reloc"

# bench reloc --runs: kept runs give the results of temporary ones, and a second call reuses
# them (nothing simulated again) with the same results.
for run in c d; do
  "$semchain" bench reloc --world "$world" --trials 3 --seed 4 \
    --methods semantic-amcl,semantic-scanmatch --runs kept --out "reloc_$run" >/dev/null 2>&1
  grep -v -E '"[a-z_]*cpu[a-z_]*_ms"' "reloc_$run/results.json" >"reloc_$run.json"
  stat -c "%i %.9Y %n" kept/trial_0/log.clf kept/mapping/map/semantic.json >"kept_$run.stamps"
done
for run in c d; do
  if ! cmp -s reloc_a.json "reloc_$run.json"; then
    echo "FAIL: bench reloc --runs ($run) differs from the run without it"
    diff reloc_a.json "reloc_$run.json" | head -20
    exit 1
  fi
done
if ! cmp -s kept_c.stamps kept_d.stamps; then
  echo "FAIL: bench reloc --runs: the second call made the runs again"
  exit 1
fi
echo "ok: bench reloc --runs"
