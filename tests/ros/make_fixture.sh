#!/usr/bin/env bash
# make_fixture.sh SEMCHAIN SOURCE_DIR WORK: what the node tests play. The map of
# two_similar_rooms from its mapping run (simulate → slam → semantic, as a user builds one); a
# trial in room A where laser-only AMCL fails (it settles 0.5 m / 43° off), exported as a bag
# without images; a trial in room B; both spliced into a kidnap bag (A, then carried to B); and
# the mapping run as a bag without images (the mapping mode's tests).
set -euo pipefail
semchain="$1"
source_dir="$2"
work="$3"
world="$source_dir/worlds/two_similar_rooms.yaml"
rm -rf "$work"
mkdir -p "$work"
"$semchain" simulate --world "$world" --out "$work/mapping" --seed 1 >/dev/null
"$semchain" slam --log "$work/mapping/log.clf" --out "$work/map" >/dev/null
"$semchain" semantic --run "$work/mapping" --map "$work/map" --out "$work/map" >/dev/null
"$semchain" simulate --world "$world" --out "$work/room_a" --route trial --start 2.1,2.4,0 \
  --seed 11 >/dev/null
"$semchain" simulate --world "$world" --out "$work/room_b" --route trial --start 8.3,3.6,2.0 \
  --seed 12 >/dev/null
"$semchain" bag export "$work/mapping" --out "$work/mapping.bag" --no-images >/dev/null
"$semchain" bag export "$work/room_a" --out "$work/room_a.bag" --no-images >/dev/null
"$semchain" bag export "$work/room_b" --out "$work/room_b.bag" --no-images >/dev/null
/usr/bin/python3 "$source_dir/tests/ros/splice_bags.py" "$work/room_a.bag" "$work/room_b.bag" \
  --out "$work/kidnap.bag" >"$work/kidnap_at.txt"
echo "fixture: map, mapping.bag, room_a.bag, room_b.bag, kidnap.bag (kidnap at $(cat "$work/kidnap_at.txt") s)"
