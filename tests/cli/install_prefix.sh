#!/usr/bin/env bash
# install_prefix.sh CMAKE BUILD_DIR SOURCE_DIR VERSION: `cmake --install` into a temporary prefix,
# the prefix moved elsewhere, then the installed semchain run from a folder outside the source
# tree, naming the shipped files as the README does (worlds/..., config/..., the default
# detector): --version, simulate, slam, semantic, detect and bench reloc on the smallest bundled
# world. The installed programs must not carry the source tree's path, and where the ROS node is
# built ROS's own lookup must find it and the package's launch files in the prefix.
set -euo pipefail
cmake="$1"
build="$2"
source_dir="$3"
version="$4"
world=worlds/low_obstacles.yaml  # the smallest bundled world: 6 m x 4 m, two objects

tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
fail() {
  echo "FAIL: $*"
  exit 1
}

"$cmake" --install "$build" --prefix "$tmp/prefix" >/dev/null
# A prefix works wherever it is moved: the programs look beside themselves, not where they were
# installed (nor in the source or build tree).
mv "$tmp/prefix" "$tmp/moved"
prefix="$tmp/moved"
semchain="$prefix/bin/semchain"
for file in bin/semchain share/semchain/config/slam.yaml share/semchain/models/detector.onnx \
  share/semchain/models/detector.names "share/semchain/$world"; do
  [ -e "$prefix/$file" ] || fail "$file is not installed"
done

# The source tree's path may appear only in the compiler's file names (assertion messages), never
# as a folder to read from.
programs=("$semchain")
ros_node="$prefix/lib/semchain/semchain_ros"
if [ -e "$build/src/ros/semchain_ros" ]; then programs+=("$ros_node"); fi
source_re="$(printf '%s' "$source_dir" | sed 's/[][\.*^$+?(){}|/]/\\&/g')"
for program in "${programs[@]}"; do
  named="$(strings -a "$program" | grep -o -E "${source_re}[^[:space:]]*" |
    grep -v -E "^${source_re}/(src|apps)/" || true)"
  [ -z "$named" ] || fail "$program names the source tree: $(echo "$named" | head -n 3)"
done

mkdir "$tmp/work"
cd "$tmp/work"
[ "$("$semchain" --version)" = "semchain $version" ] || fail "--version: $("$semchain" --version)"

"$semchain" simulate --world "$world" --out sim --seed 1 >/dev/null
[ -s sim/log.clf ] && [ -s sim/frames/000010.png ] || fail "simulate wrote no log or frames"
"$semchain" slam --log sim/log.clf --config config/slam.yaml --out map >/dev/null
[ -s map/map.yaml ] || fail "slam wrote no map"
"$semchain" semantic --run sim --map map --out map >/dev/null
[ -s map/semantic.json ] || fail "semantic wrote no semantic.json"
# No --model: the shipped detector.
"$semchain" detect --images sim/frames/000010.png --out detect >/dev/null
[ -s detect/detections.jsonl ] || fail "detect wrote no detections.jsonl"
"$semchain" bench reloc --world "$world" --trials 1 --methods semantic-scanmatch --out reloc \
  >/dev/null
[ -s reloc/results.json ] || fail "bench reloc wrote no results.json"
# A relative path that is neither here nor shipped: the error names what the user wrote.
if "$semchain" simulate --world worlds/no_such_world.yaml --out missing 2>err.txt; then
  fail "a missing world was accepted"
fi
grep -q "worlds/no_such_world.yaml" err.txt || fail "unclear error: $(cat err.txt)"
echo "ok: installed semchain ran simulate, slam, semantic, detect and bench reloc"

if [ "${#programs[@]}" -gt 1 ]; then
  # ROS's tools find a package's nodes in PREFIX/lib/<package> of a prefix on CMAKE_PREFIX_PATH
  # (marked by PREFIX/.catkin), and its files through ROS_PACKAGE_PATH.
  found="$(CMAKE_PREFIX_PATH="$prefix" ROS_PACKAGE_PATH="$prefix/share" /usr/bin/python3 -c \
    'import roslib.packages as p; print(p.find_node("semchain", "semchain_ros")[0])')"
  [ "$found" = "$ros_node" ] || fail "ROS finds semchain_ros at '$found', not $ros_node"
  launch="$(CMAKE_PREFIX_PATH="$prefix" ROS_PACKAGE_PATH="$prefix/share" /usr/bin/python3 -c \
    'import roslib.packages as p; print(p.find_resource("semchain", "semchain_mapping.launch")[0])')"
  [ "$launch" = "$prefix/share/semchain/config/ros/semchain_mapping.launch" ] ||
    fail "ROS finds semchain_mapping.launch at '$launch'"
  echo "ok: ROS finds the installed semchain_ros and its launch files"
fi
