#!/usr/bin/env bash
# readme_commands_test.sh BUILD_DIR REPO_ROOT: the README's quick commands must run as written.
#
# Runs every fenced ```bash block of REPO_ROOT/README.md whose fence is directly preceded by the
# line <!-- readme-test -->, in README order, each as its own `bash` with `set -euo pipefail`
# and with BUILD_DIR/apps first on the PATH (where `semchain` is built). All blocks run in one
# temporary directory, as a reader would run them one after the other, so a block may use what an
# earlier one wrote; the directory holds links to the repository's worlds/, config/ and models/,
# so the README's relative paths work. Fails (exit 1) naming the first line of every block that
# failed, and when the README has no marked block at all.
set -euo pipefail

if [ "$#" -ne 2 ]; then
  echo "usage: $0 BUILD_DIR REPO_ROOT" >&2
  exit 2
fi
build="$(cd "$1" && pwd)"
root="$(cd "$2" && pwd)"
readme="$root/README.md"
[ -f "$readme" ] || { echo "FAIL: $readme not found"; exit 1; }
[ -x "$build/apps/semchain" ] || { echo "FAIL: $build/apps/semchain not built"; exit 1; }

work="$(mktemp -d "${TMPDIR:-/tmp}/readme_commands.XXXXXX")"
trap 'rm -rf "$work"' EXIT
for folder in worlds config models; do
  [ -e "$root/$folder" ] && ln -s "$root/$folder" "$work/$folder"
done
mkdir "$work/blocks"

# Split the marked blocks into blocks/NNN.sh. A marker applies only to the line right after it.
awk -v dir="$work/blocks" '
  function trim(s) { sub(/^[ \t]+/, "", s); sub(/[ \t\r]+$/, "", s); return s }
  inblock {
    if (trim($0) ~ /^```$/) { inblock = 0; close(file); next }
    print > file
    next
  }
  {
    line = trim($0)
    if (marked && line ~ /^```bash$/) {
      n++
      file = sprintf("%s/%03d.sh", dir, n)
      printf "" > file
      inblock = 1
    } else if (marked && line ~ /^```/) {
      printf "README.md:%d: <!-- readme-test --> is followed by a fence that is not ```bash\n", NR > "/dev/stderr"
      bad = 1
    }
    marked = (line == "<!-- readme-test -->")
  }
  END {
    if (inblock) { print "README.md: a marked block is never closed" > "/dev/stderr"; exit 1 }
    if (bad) exit 1
  }
' "$readme" || { echo "FAIL: README.md's marked blocks cannot be read"; exit 1; }

shopt -s nullglob
blocks=("$work"/blocks/*.sh)
if [ "${#blocks[@]}" -eq 0 ]; then
  echo "FAIL: README.md has no block marked <!-- readme-test -->"
  exit 1
fi

failed=()
for block in "${blocks[@]}"; do
  first="$(grep -m1 -v '^[[:space:]]*$' "$block" || true)"
  echo "== README block: $first"
  if (cd "$work" && PATH="$build/apps:$PATH" bash -c "set -euo pipefail
$(cat "$block")"); then
    echo "   ok"
  else
    echo "   FAILED (exit $?)"
    failed+=("$first")
  fi
done

if [ "${#failed[@]}" -gt 0 ]; then
  for first in "${failed[@]}"; do
    echo "FAIL: the README block starting '$first' failed"
  done
  exit 1
fi
echo "All ${#blocks[@]} marked README blocks ran."
