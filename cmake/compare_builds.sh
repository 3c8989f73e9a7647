#!/bin/sh
# Checks that two builds of boxsim give bit-identical trajectories: runs every shipped scene
# (chapters/impulse_damped/scenes, chapters/basic_colliding/scenes) under every technique with
# each build's `boxsim run` and compares the trajectory files byte for byte.
#
#   cmake --preset default && cmake --build --preset default
#   cmake --preset debug && cmake --build --preset debug
#   cmake/compare_builds.sh build build-debug [duration_s] [timeout_s]
#
# Prints one line per scene and technique: "same", "DIFFERENT" (with the first differing byte)
# or "skipped" when a run failed or took longer than timeout_s (default 120 s) in either build
# (an unoptimised build is slow on the large clumps). Exit status 1 when any pair differs.
set -u
if [ $# -lt 2 ]; then
  echo "usage: $0 BUILD_DIR_A BUILD_DIR_B [duration_s (default 2)] [timeout_s (default 120)]" >&2
  exit 2
fi
a=$1
b=$2
duration=${3:-2}
limit=${4:-120}
source_dir=$(cd "$(dirname "$0")/.." && pwd)
for build in "$a" "$b"; do
  if [ ! -x "$build/boxsim" ]; then
    echo "$0: no $build/boxsim; build it first (cmake --build $build --target boxsim)" >&2
    exit 2
  fi
done
methods=$("$a/boxsim" run --help | sed -n 's/.*Technique: \([a-z_, ]*\).*/\1/p' | tr -d ',')
if [ -z "$methods" ]; then
  echo "$0: could not read the technique list from '$a/boxsim run --help'" >&2
  exit 2
fi
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
status=0
for scene in "$source_dir"/chapters/impulse_damped/scenes/*.json \
             "$source_dir"/chapters/basic_colliding/scenes/*.json; do
  name=$(basename "$(dirname "$(dirname "$scene")")")/$(basename "$scene" .json)
  for method in $methods; do
    if timeout "$limit" "$a/boxsim" run "$scene" -m "$method" -t "$duration" -q -o "$out/a.dat" 2>/dev/null &&
       timeout "$limit" "$b/boxsim" run "$scene" -m "$method" -t "$duration" -q -o "$out/b.dat" 2>/dev/null; then
      if difference=$(cmp "$out/a.dat" "$out/b.dat" 2>&1); then
        echo "same       $name $method"
      else
        echo "DIFFERENT  $name $method: $difference"
        status=1
      fi
    else
      echo "skipped    $name $method (failed or over ${limit} s)"
    fi
    rm -f "$out/a.dat" "$out/b.dat"
  done
done
exit $status
