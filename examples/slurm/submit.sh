#!/bin/bash
# Submits the shards as a job array and the merge as a job that starts when every shard has ended:
#   ./submit.sh [SHARDS]        (default 4; SCENE, FRAMES, FORMAT and OUTPUT pass through to the jobs)
# A shard that failed or was cancelled left no part, and the merge says which (parts/merge.log):
# rerun that one shard with `FVRML_SHARDS=M sbatch --array=K shards.sbatch` (so that the one task
# knows it is shard K of M), then `sbatch merge.sbatch`.
set -euo pipefail
cd "$(dirname "$0")"
shards="${1:-4}"
export FVRML_SHARDS="$shards"
mkdir -p parts
array=$(sbatch --parsable --export=ALL --array="0-$((shards - 1))" shards.sbatch)
sbatch --parsable --export=ALL --dependency="afterany:${array}" merge.sbatch
