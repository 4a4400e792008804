#!/bin/bash
# Submit a study as a Slurm job array of N shards plus a merge job that runs when all
# shards have succeeded:
#
#   scripts/slurm/submit.sh STUDY OUTDIR [N]      (N defaults to 16)
set -euo pipefail
STUDY=${1:?usage: submit.sh STUDY OUTDIR [N]}
OUT=${2:?usage: submit.sh STUDY OUTDIR [N]}
N=${3:-16}
HERE=$(cd "$(dirname "$0")" && pwd)
ARRAY=$(sbatch --parsable --array="1-$N" "$HERE/bench-shard.sbatch" "$STUDY" "$OUT")
ARRAY=${ARRAY%%;*}
MERGE=$(sbatch --parsable --dependency="afterok:$ARRAY" "$HERE/bench-merge.sbatch" "$OUT")
echo "shards: job $ARRAY (array 1-$N); merge and report: job ${MERGE%%;*}"
