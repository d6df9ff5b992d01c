#!/usr/bin/env bash
# Peers, whole process against whole process: Debian's f3d and manylight render the sweep's
# room (uniform layout, generators/light_layouts.h) to a PNG at 640x480 with Mesa's shader cache
# off, as in a fresh container. f3d 1.3.1 needs an X display (without one it crashes), so it
# runs on Xvfb when there is no DISPLAY. Writes CSV: tool,lights,seconds,result.
# Usage: bench/peers.sh OUT.csv [COUNTS]   (default counts "64 512 4096 65536"; run from the
# repository root after a build; f3d: `ci/install-deps.sh --peers`)
set -euo pipefail
out="$1"
counts="${2:-64 512 4096 65536}"
limit=600  # seconds before a run counts as hung
bin="$PWD/build/bin"
work="$(mktemp -d)"
xvfb_pid=""
cleanup() {
  [ -n "$xvfb_pid" ] && kill "$xvfb_pid" 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT
export MESA_SHADER_CACHE_DISABLE=true

# Runs "$@" under the time limit; prints "SECONDS RESULT".
timed() {
  local png="$1"
  shift
  local start end rc=0
  start=$(date +%s.%N)
  timeout "$limit" "$@" >"$work/log" 2>&1 || rc=$?
  end=$(date +%s.%N)
  local result="ok"
  if [ "$rc" -eq 124 ]; then
    result="no image after ${limit} s (stopped)"
  elif [ "$rc" -ne 0 ]; then
    result="failed: exit $rc$( [ "$rc" -ge 128 ] && echo " (signal $((rc - 128)))")"
  elif [ ! -s "$png" ]; then
    result="failed: no image written"
  fi
  awk -v a="$start" -v b="$end" -v r="$result" 'BEGIN { printf "%.2f %s\n", b - a, r }'
}

echo "tool,lights,seconds,result" >"$work/peers.csv"
row() { # tool lights "SECONDS RESULT"
  echo "$1,$2,${3%% *},\"${3#* }\"" >>"$work/peers.csv"
}
f3d_bin="$(command -v f3d || true)"
if [ -n "$f3d_bin" ] && [ -z "${DISPLAY:-}" ]; then
  # What a headless user meets first: f3d without a display.
  "$bin/manylight_make_scene" "$work/probe.gltf" 64 --layout uniform
  row "f3d (no display)" 64 "$(timed "$work/probe.png" "$f3d_bin" --output "$work/probe.png" --resolution 640,480 "$work/probe.gltf")"
  command -v Xvfb >/dev/null || { echo "peers.sh: f3d needs Xvfb here (ci/install-deps.sh --peers)" >&2; exit 1; }
  Xvfb :87 -screen 0 1280x1024x24 >/dev/null 2>&1 &
  xvfb_pid=$!
  export DISPLAY=:87
  sleep 2
fi
for n in $counts; do
  scene="$work/room$n.gltf"
  "$bin/manylight_make_scene" "$scene" "$n" --layout uniform
  for method in reference lightcuts; do
    rm -f "$work/m.png"
    row "manylight --method $method" "$n" "$(timed "$work/m.png" "$bin/manylight" render "$scene" -o "$work/m.png" --size 640x480 --method "$method")"
  done
  if [ -n "$f3d_bin" ]; then
    rm -f "$work/f.png"
    row "f3d $("$f3d_bin" --version 2>/dev/null | head -1 | awk '{print $2}')" "$n" "$(timed "$work/f.png" "$f3d_bin" --output "$work/f.png" --resolution 640,480 "$scene")"
  fi
  echo "peers.sh: $n lights done" >&2
done
mkdir -p "$(dirname "$out")"
mv "$work/peers.csv" "$out"
