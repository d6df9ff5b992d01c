#!/usr/bin/env bash
# Kiosk playback speed: frames per second of `manylight play` on a baked room scene with
# LIGHTS lights (default 65,536, mixed point/spot/directional) at 640×360 with lightcuts
# (ε = 0.02, node rule), frames streamed to /dev/null: the default turntable of FRAMES
# frames (default 120, a full turn), with the cuts kept per cell of the scene from frame to
# frame (play's default) and with every frame's cuts found anew (--fresh-cuts). Prints the
# rendering frame rate (the frames' GL work and CPU cuts) and the overall one (with reading
# back and encoding).
# Usage: bench/playback_fps.sh [LIGHTS] [FRAMES]   (run from the repository root after a build)
set -euo pipefail
lights="${1:-65536}"
frames="${2:-120}"
bin="$PWD/build/bin"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
"$bin/manylight_make_scene" "$work/room.glb" "$lights" 1 >/dev/null
"$bin/manylight" bake "$work/room.glb" -o "$work/room.mlbake" >/dev/null
for cuts in kept fresh; do
  flag=()
  [ "$cuts" = fresh ] && flag=(--fresh-cuts)
  "$bin/manylight" play "$work/room.mlbake" -o - --frames "$frames" --size 640x360 \
    --method lightcuts "${flag[@]}" --stats "$work/stats.json" > /dev/null
  python3 - "$work/stats.json" "$lights" "$cuts" <<'PY'
import json, statistics, sys
s = json.load(open(sys.argv[1]))
ms = s["frame_render_ms"]
later = ms[1:] or ms
print(f"{sys.argv[2]} lights, {s['frames']} frames at {s['width']}x{s['height']} on {s['renderer']}, "
      f"cuts {sys.argv[3]}: {s['render_fps']:.2f} fps rendering, {s['wall_fps']:.2f} fps overall "
      f"(first frame {ms[0]:.0f} ms with shader compilation, later {min(later):.0f}-{max(later):.0f} ms, "
      f"median {statistics.median(later):.0f})")
PY
done
