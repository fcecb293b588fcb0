#!/usr/bin/env bash
# LODs for a library of scenes as a Slurm job array: each array task runs one
# shard of the manifest; the shards split the list round robin and write
# disjoint outputs, so they need no coordination.
#
#   sbatch --array=0-15 examples/slurm_lod_batch.sh library.txt out/
#   # when all tasks are done:
#   lodforge report out/reports/*.json -o out/report.json
#
# library.txt lists one scene per line (paths relative to its folder are
# mirrored under out/). Set the number of shards with --array=0-(N-1).
#SBATCH --job-name=lodforge-lod
#SBATCH --cpus-per-task=4
#SBATCH --mem=8G
#SBATCH --time=04:00:00
#SBATCH --output=lodforge-lod-%A_%a.log
set -euo pipefail

manifest=${1:?usage: sbatch --array=0-N-1 slurm_lod_batch.sh MANIFEST OUT_DIR}
out_dir=${2:?usage: sbatch --array=0-N-1 slurm_lod_batch.sh MANIFEST OUT_DIR}
lodforge=${LODFORGE:-lodforge}

mkdir -p "$out_dir/reports"
"$lodforge" lod --manifest "$manifest" \
  --shard "$SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT" \
  --threads "${SLURM_CPUS_PER_TASK:-0}" \
  --out-dir "$out_dir" \
  --report "$out_dir/reports/shard-$SLURM_ARRAY_TASK_ID.json" \
  --quiet
