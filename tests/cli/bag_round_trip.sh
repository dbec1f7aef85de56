#!/usr/bin/env bash
# semchain bag: a simulated run exported to a bag and imported again is a run that slam reads;
# the bag's topics are those of DESIGN.md section 5.7.
#   bag_round_trip.sh SEMCHAIN WORLD OUT_DIR
set -eu
semchain="$1"
world="$2"
out="$3"
rm -rf "$out"
mkdir -p "$out"
"$semchain" simulate --world "$world" --out "$out/run" --seed 3 --route trial --start 3.0,3.5,0.3 \
  >/dev/null
"$semchain" bag export "$out/run" --out "$out/run.bag" >/dev/null
"$semchain" bag import "$out/run.bag" --out "$out/imported" >/dev/null
for file in log.clf truth.txt camera.yaml detections.jsonl world.yaml run.yaml frames/000000.png \
  frames/000000_depth.png; do
  if [ ! -s "$out/imported/$file" ]; then
    echo "FAIL: bag import wrote no $file"
    exit 1
  fi
done
if ! cmp -s "$out/run/camera.yaml" "$out/imported/camera.yaml"; then
  echo "FAIL: camera.yaml changed on the way through the bag"
  exit 1
fi
if ! cmp -s "$out/run/frames/000003.png" "$out/imported/frames/000003.png"; then
  echo "FAIL: frames/000003.png changed on the way through the bag"
  exit 1
fi
"$semchain" slam --log "$out/imported/log.clf" --out "$out/map" >/dev/null 2>&1
if [ ! -s "$out/map/trajectory.txt" ]; then
  echo "FAIL: slam wrote no trajectory for the imported run"
  exit 1
fi
if [ -x /usr/bin/rosbag ]; then
  # ROS's own tool reads the bag and sees the topics of DESIGN.md section 5.7.
  topics="$(/usr/bin/python3 /usr/bin/rosbag info "$out/run.bag")"
  for topic in /scan /tf /tf_static /odom /camera/color/image_raw /camera/depth/image_raw \
    /camera/color/camera_info /semchain/detections /semchain/truth; do
    if ! grep -q -- "$topic " <<<"$topics"; then
      echo "FAIL: rosbag info does not list $topic"
      exit 1
    fi
  done
fi
echo "bag round trip: ok"
