#!/usr/bin/env bash
# The one command behind docs/benchmarks.md, docs/stability.md and docs/charts/: the
# speed/accuracy sweep and the stability suite (`manylight bench`), the peers when f3d is
# installed (bench/peers.sh), then the charts and pages (bench/report.py, gnuplot).
# Run from the repository root after the build (README.md, the first command):
#   bench/sweep.sh            the full sweep: 640x480, 6 layouts x 6 counts up to 1,048,576,
#                             every method, ε and mode (hours on a 2-core machine; see
#                             docs/performance.md): what docs/ shows
#   bench/sweep.sh --quick    the same at 320x240
#   bench/sweep.sh --resume   go on with an interrupted sweep: finished cases are kept (the
#                             same build's only: manylight refuses another build's results)
#   bench/sweep.sh --report   only redraw the charts and pages from docs/results/
# Results (CSV and JSON) go to docs/results/, rewritten after every case.
set -euo pipefail
size=640x480
resume=()
report_only=false
for a in "$@"; do
  case "$a" in
    --quick) size=320x240 ;;
    --resume) resume=(--resume) ;;
    --report) report_only=true ;;
    *) echo "usage: bench/sweep.sh [--quick] [--resume] [--report]" >&2; exit 2 ;;
  esac
done
bin="$PWD/build/bin"
results="$PWD/docs/results"
mkdir -p "$results"
if ! $report_only; then
  # Fail now, not after hours of sweep: the peers step needs the scene generator too.
  for tool in manylight manylight_make_scene; do
    if [ ! -x "$bin/$tool" ]; then
      echo "sweep.sh: $bin/$tool is missing; build everything first (cmake --build build)" >&2
      exit 2
    fi
  done
  "$bin/manylight" bench --size "$size" "${resume[@]}" \
    --csv "$results/sweep.csv" --json "$results/sweep.json"
  "$bin/manylight" bench --suite stability "${resume[@]}" \
    --csv "$results/stability.csv" --json "$results/stability.json"
  if command -v f3d >/dev/null; then
    bench/peers.sh "$results/peers.csv"
  else
    echo "sweep.sh: f3d is not installed (ci/install-deps.sh --peers); peers not measured" >&2
  fi
fi
python3 bench/report.py "$results" docs
echo "sweep.sh: docs/benchmarks.md, docs/stability.md and docs/charts/ written"
