#!/usr/bin/env bash
# Kiosk playback speed: frames per second of `manylight play` on a baked room scene with
# LIGHTS lights (default 65,536, mixed point/spot/directional) at 640×360 with lightcuts
# (ε = 0.02, node rule), frames streamed to /dev/null. Prints the rendering frame rate (GPU
# work of the frames) and the overall one (with reading back and encoding).
# Usage: bench/playback_fps.sh [LIGHTS] [FRAMES]   (run from the repository root after a build)
set -euo pipefail
lights="${1:-65536}"
frames="${2:-5}"
bin="$PWD/build/bin"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
"$bin/manylight_make_scene" "$work/room.glb" "$lights" 1 >/dev/null
"$bin/manylight" bake "$work/room.glb" -o "$work/room.mlbake" >/dev/null
"$bin/manylight" play "$work/room.mlbake" -o - --frames "$frames" --size 640x360 --method lightcuts \
  --stats "$work/stats.json" > /dev/null
python3 - "$work/stats.json" "$lights" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
ms = s["frame_render_ms"]
print(f"{sys.argv[2]} lights, {s['frames']} frames at {s['width']}x{s['height']} on {s['renderer']}: "
      f"{s['render_fps']:.3f} fps rendering, {s['wall_fps']:.3f} fps overall "
      f"(first frame {ms[0]:.0f} ms with shader compilation, later {min(ms[1:] or ms):.0f}-{max(ms[1:] or ms):.0f} ms)")
PY
