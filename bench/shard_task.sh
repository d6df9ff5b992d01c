#!/usr/bin/env bash
# One task of a thumbnail farm (docs/scale-out.md): renders shard I of N of the scenes listed
# in LIST (one path a line, absolute or relative to the working folder; blank lines and lines
# starting with # are skipped) into OUT_DIR with `manylight render --out-dir OUT_DIR --shard
# I/N`, passing on any further render options, and writes that shard's stats to
# OUT_DIR/shard-I-of-N.json. I and N come from the scheduler: JOB_COMPLETION_INDEX (a
# Kubernetes Indexed Job) with SHARD_COUNT (the Job's completions), or SLURM_ARRAY_TASK_ID,
# SLURM_ARRAY_TASK_MIN and SLURM_ARRAY_TASK_COUNT (a Slurm job array over a range without
# steps). The exit code is manylight's: 1 when a scene of the shard failed.
# Usage: bench/shard_task.sh LIST OUT_DIR [render options...]
set -euo pipefail
if [[ $# -lt 2 ]]; then
  echo "usage: shard_task.sh LIST OUT_DIR [render options...]" >&2
  exit 2
fi
list="$1" out="$2"
shift 2
if [[ -n "${JOB_COMPLETION_INDEX:-}" ]]; then
  index="$JOB_COMPLETION_INDEX"
  count="${SHARD_COUNT:?shard_task.sh: set SHARD_COUNT to spec.completions of the Job}"
elif [[ -n "${SLURM_ARRAY_TASK_ID:-}" ]]; then
  index=$((SLURM_ARRAY_TASK_ID - ${SLURM_ARRAY_TASK_MIN:-0}))
  count="$SLURM_ARRAY_TASK_COUNT"
else
  echo "shard_task.sh: no task index: set JOB_COMPLETION_INDEX and SHARD_COUNT, or" \
    "SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT" >&2
  exit 2
fi
scenes=()
while IFS= read -r line || [[ -n "$line" ]]; do
  [[ -z "$line" || "$line" == \#* ]] || scenes+=("$line")
done <"$list"
manylight="${MANYLIGHT:-$(dirname "$0")/../build/bin/manylight}"
exec "$manylight" render "${scenes[@]}" --out-dir "$out" --shard "$index/$count" \
  --stats "$out/shard-$index-of-$count.json" "$@"
