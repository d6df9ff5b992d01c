#!/usr/bin/env bash
# The steps ci/Dockerfile runs to build its image, runnable on any Debian 12 machine (as root
# or with sudo) and run by .ci/run, so the container recipe is tested where there is no
# Docker engine: install the packages, build, run the whole test suite (the README's second
# command), then render the sample scene twice and check the reruns are bit-identical.
set -euo pipefail
cd "$(dirname "$0")/.."
ci/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build
ctest --test-dir build --output-on-failure -j2
build/bin/manylight render scenes/sample.gltf -o out/sample.png
build/bin/manylight render scenes/sample.gltf -o out/sample-rerun.png
build/bin/manylight compare out/sample.png out/sample-rerun.png
