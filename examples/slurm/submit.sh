#!/bin/bash
# Submits the shards as a job array and the merge as a job that starts when every shard succeeded:
#   ./submit.sh [SHARDS]        (default 4; SCENE, FRAMES and OUTPUT pass through to the jobs)
# A failed or cancelled shard leaves the merge pending (afterok); rerun that one shard with
# `sbatch --array=K shards.sbatch`, then `sbatch merge.sbatch` (the merge names any part missing).
set -euo pipefail
cd "$(dirname "$0")"
shards="${1:-4}"
mkdir -p parts
array=$(sbatch --parsable --export=ALL --array="0-$((shards - 1))" shards.sbatch)
sbatch --parsable --export=ALL --dependency="afterok:${array}" merge.sbatch
