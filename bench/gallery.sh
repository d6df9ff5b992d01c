#!/usr/bin/env bash
# The gallery: every renderable real asset of ../shared/scenes (when that folder exists; not
# the validator and defect collections) and the project's own scenes/, each rendered with the
# bare `render` command (its defaults: thumbnail framing, default rig, auto exposure, PBR
# Neutral), in one contact sheet with their names, and the Cornell-like room without and with
# indirect light. Look at it before and after any change to shading, loading or output.
# Usage: bench/gallery.sh [OUT.png [render options...]]   (default docs/gallery.png; run from
# the repository root after a build). With GALLERY_RENDERS=DIR each scene's render is kept
# there too (DIR/NAME.png), for bench/clipped_black.py DIR.
set -euo pipefail
out="${1:-docs/gallery.png}"
shift || true
bin="$PWD/build/bin"
shared="$PWD/../shared/scenes"
font=/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf  # fonts-dejavu-core (ci/install-deps.sh)
tile=200x150
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
files=(scenes/*.gltf)
if [ -d "$shared" ]; then
  skip='/(BlenderIO-edge-cases|MagnumGltfImporterTests|glTF-Validator-tests|glTF-Asset-Generator-Compatibility|glTFast-test-models|tinygltf-defects|assimp-glTF2-defects)/'
  while IFS= read -r f; do files+=("$f"); done < <(find "$shared" \( -name '*.gltf' -o -name '*.glb' \) | grep -v -E "$skip" | LC_ALL=C sort)
fi
tiles=()
i=0
# One tile: render FILE (with OPTIONS after the gallery's own) and label it LABEL.
add_tile() {
  local f="$1" name="$2"
  shift 2
  i=$((i + 1))
  local label="$name"
  if ! "$bin/manylight" render "$f" -o "$work/r$i.png" --size "$size" ${options[@]+"${options[@]}"} "$@" 2>"$work/e$i.txt"; then
    oiiotool --pattern constant:color=0,0,0,0 "$tile" 4 -o "$work/r$i.png"
    label="$name: refused"
  fi
  oiiotool "$work/r$i.png" --pattern constant:color=0.2,0.2,0.23,1 "$tile" 4 --over \
    --text:x=4:y=145:size=11:color=0.9,0.9,0.9,1:font="$font" "$label" -o "$work/t$(printf %03d $i).png"
  tiles+=("$work/t$(printf %03d $i).png")
  if [ -n "${GALLERY_RENDERS:-}" ]; then
    mkdir -p "$GALLERY_RENDERS"
    cp "$work/r$i.png" "$GALLERY_RENDERS/$(printf %s "$name" | tr '/: ' '___' | sed 's/\.[^.]*$//').png"
  fi
}
options=("$@")
size="$tile"
for f in "${files[@]}"; do
  name="${f#"$shared"/}"
  add_tile "$f" "${name//\/glTF\//\/}"
done
# The Cornell-like room of docs/indirect.md with a block: direct light only, then one bounce
# from the light caches and the exact gather. Indirect light has no visibility: no indirect
# shadow at the block's foot, and the block's own faces lit through it.
# A variant's own options (OUT.png OPTIONS...) may set --indirect too: then the room is left out.
if [ ${#options[@]} -eq 0 ]; then
  "$bin/manylight_make_scene" "$work/cornell.glb" 1 --cornell --block >/dev/null
  size=200x130  # the label below the room's bright floor
  add_tile "$work/cornell.glb" "cornell: direct only" --indirect none
  add_tile "$work/cornell.glb" "cornell: --indirect caches" --indirect caches
  add_tile "$work/cornell.glb" "cornell: --indirect exact" --indirect exact
fi
columns=6
rows=$(((${#tiles[@]} + columns - 1) / columns))
mkdir -p "$(dirname "$out")"
oiiotool "${tiles[@]}" --mosaic:pad=2 "${columns}x${rows}" -o "$out"
echo "gallery.sh: ${#tiles[@]} scenes into $out"
