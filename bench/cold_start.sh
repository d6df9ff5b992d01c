#!/usr/bin/env bash
# Whole-process time of one render as a fresh container sees it: Mesa's shader cache off,
# so llvmpipe compiles every shader. A 512-light room (textured, mixed point/spot/
# directional) at 640×480 with the reference method, RUNS times; prints each run's wall
# time and the median and fastest. Run-to-run noise on a shared 2-core machine is large,
# so read the median.
# Usage: bench/cold_start.sh [LIGHTS] [RUNS]   (run from the repository root after a build)
set -euo pipefail
lights="${1:-512}"
runs="${2:-9}"
bin="$PWD/build/bin"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
"$bin/manylight_make_scene" "$work/room.gltf" "$lights" >/dev/null
for ((i = 0; i < runs; ++i)); do
  start=$(date +%s.%N)
  MESA_SHADER_CACHE_DISABLE=true "$bin/manylight" render "$work/room.gltf" -o "$work/out.png"
  end=$(date +%s.%N)
  echo "$start $end"
done | python3 -c '
import sys, statistics
t = [float(b) - float(a) for a, b in (line.split() for line in sys.stdin)]
print("runs (s):", " ".join(f"{x:.2f}" for x in t))
print(f"'"$lights"' lights, 640x480, reference, cold shader cache: median {statistics.median(t):.2f} s, fastest {min(t):.2f} s over {len(t)} runs")'
