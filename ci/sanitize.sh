#!/usr/bin/env bash
# CI: the scene tests and the corpus walk under AddressSanitizer + UndefinedBehaviorSanitizer,
# then the libFuzzer targets for a bounded time: the glTF loader (FUZZ_SECONDS, seeded with
# ../shared/scenes and generated Draco and meshopt GLBs), the light list reader and the baked
# file reader (a third of that each, seeded with small lists and small baked scenes).
# Usage: ci/sanitize.sh [FUZZ_SECONDS]   (default 60)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DMANYLIGHT_SANITIZE=ON -DMANYLIGHT_FUZZ=ON -DMANYLIGHT_BENCH=OFF
cmake --build build-asan --target manylight_tests manylight_gltests manylight manylight_fuzz_gltf_loader \
  manylight_fuzz_light_list manylight_fuzz_baked_file manylight_imageio
# Slow unwinding gives full allocation stacks, which the third-party suppressions match.
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:fast_unwind_on_malloc=0
export LSAN_OPTIONS="suppressions=$PWD/ci/lsan-suppressions.txt"
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1

# LeakSanitizer's stop-the-world tracer itself now and then dies with SIGSEGV at exit ("Tracer
# caught signal 11", google/sanitizers#1353): the leak check never ran, so there is no finding.
# Such a run, where no test failed, is run once more; a second one, or any other failure, fails.
leak_checked() {
  local log status=0
  log="$(mktemp)"
  "$@" 2>&1 | tee "$log" || status=$?
  if [ "$status" -ne 0 ] && grep -q 'Tracer caught signal' "$log" \
    && grep -q 'LeakSanitizer has encountered a fatal error' "$log" && ! grep -q '^\[  FAILED  \]' "$log"; then
    echo "ci/sanitize.sh: LeakSanitizer's tracer died, not a finding; running $1 once more"
    status=0
    "$@" || status=$?
  fi
  rm -f "$log"
  return "$status"
}
leak_checked build-asan/bin/manylight_tests
# The corpus walk that renders every file (GL through llvmpipe). Leak checking is off for it:
# Mesa's own allocations at exit are not ours to judge; address and UB checks stay on.
ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 build-asan/bin/manylight_gltests --gtest_filter='Corpus.*'

# Fuzzing: seeds are the corpus's small files, copied to a scratch folder (never the repo).
corpus="$(mktemp -d)"
lists="$(mktemp -d)"
bakes="$(mktemp -d)"
trap 'rm -rf "$corpus" "$lists" "$bakes"' EXIT
if [ -d ../shared/scenes ]; then
  find ../shared/scenes -type f \( -name '*.gltf' -o -name '*.glb' \) -size -256k -exec cp -t "$corpus" {} + 2>/dev/null || true
fi
cp scenes/*.gltf "$corpus"/
# Self-contained Draco and meshopt GLBs, so that the fuzzing reaches their decoders.
MANYLIGHT_FUZZ_SEEDS="$corpus" build-asan/bin/manylight_tests --gtest_filter='Compression.FuzzSeedsLoad' >/dev/null
# -detect_leaks=0: LeakSanitizer's per-input check itself died with SIGSEGV in its tracer
# here (an empty "crash" input), which is not a finding; the test run above checks leaks.
build-asan/bin/manylight_fuzz_gltf_loader -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
  -detect_leaks=0 -artifact_prefix=build-asan/ "$corpus"

# Light lists: the first byte of an input picks the format (0 CSV, 1 JSON, 2 the UE4 dump).
printf '\000x,y,z,r,g,b,brightness,radius,falloff\n1,2,3,255,76,216,5000,250,inverse-square\n' > "$lists/csv"
printf '\001{"lights": [{"position": [1, 2, 3], "color": [255, 76, 216], "brightness": 5, "radius": 2}]}' > "$lists/json"
printf '\002GUID C2C1 - Position X=-300.000 Y=0.000 Z=150.000 W=1.000 - Radius 250 - Color (R=255,G=76,B=216,A=0) - Brightness = 5000\n' > "$lists/dump"
build-asan/bin/manylight_fuzz_light_list -max_total_time="$(( seconds / 3 + 1 ))" -timeout=10 -rss_limit_mb=2048 \
  -detect_leaks=0 -artifact_prefix=build-asan/ "$lists"

# Baked files: the seed is the sample's bake without its 32-byte header (the target writes one).
ASAN_OPTIONS=detect_leaks=0 build-asan/bin/manylight bake scenes/sample.gltf -o "$bakes/a.mlbake" >/dev/null
mkdir "$bakes/seeds"
tail -c +33 "$bakes/a.mlbake" > "$bakes/seeds/a"
build-asan/bin/manylight_fuzz_baked_file -max_total_time="$(( seconds / 3 + 1 ))" -timeout=10 -rss_limit_mb=2048 \
  -detect_leaks=0 -artifact_prefix=build-asan/ "$bakes/seeds"
