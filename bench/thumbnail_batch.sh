#!/usr/bin/env bash
# Thumbnails in one process (render --out-dir) against one process per file, on N generated
# scenes (room scenes with 8 lights each, textured) at 256×256. Prints the time per
# thumbnail both ways.
# Usage: bench/thumbnail_batch.sh [N]   (default 20; run from the repository root after a build)
set -euo pipefail
n="${1:-20}"
bin="$PWD/build/bin"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
scenes=()
for i in $(seq 1 "$n"); do
  "$bin/manylight_make_scene" "$work/scene$i.glb" 8 "$i" >/dev/null
  scenes+=("$work/scene$i.glb")
done
now() { date +%s.%N; }
start=$(now)
"$bin/manylight" render "${scenes[@]}" --out-dir "$work/batch" --size 256x256 2>/dev/null
batch=$(awk -v a="$start" -v b="$(now)" -v n="$n" 'BEGIN { print (b - a) * 1000 / n }')
start=$(now)
for s in "${scenes[@]}"; do
  "$bin/manylight" render "$s" -o "$work/single/$(basename "$s" .glb).png" --size 256x256 2>/dev/null
done
single=$(awk -v a="$start" -v b="$(now)" -v n="$n" 'BEGIN { print (b - a) * 1000 / n }')
for s in "${scenes[@]}"; do
  name="$(basename "$s" .glb).png"
  cmp -s "$work/batch/$name" "$work/single/$name" || { echo "$name differs between the two runs" >&2; exit 1; }
done
printf '%d thumbnails at 256x256: one process %.0f ms each, one process per file %.0f ms each (%.1fx)\n' \
  "$n" "$batch" "$single" "$(awk -v a="$single" -v b="$batch" 'BEGIN { print a / b }')"
