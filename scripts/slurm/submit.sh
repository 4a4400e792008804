#!/bin/bash
# Submit a study as a Slurm job array of N shards plus a merge job that runs when all
# shards have succeeded:
#
#   scripts/slurm/submit.sh STUDY OUTDIR [N]      (N defaults to 16)
#   MAPS=maps/ scripts/slurm/submit.sh faigl2013-real OUTDIR [N]   (a map-folder suite)
set -euo pipefail
STUDY=${1:?usage: submit.sh STUDY OUTDIR [N]}
OUT=${2:?usage: submit.sh STUDY OUTDIR [N]}
N=${3:-16}
HERE=$(cd "$(dirname "$0")" && pwd)
# The shards run elsewhere, so they get the folder's absolute path (sbatch passes the
# environment on).
if [[ -n ${MAPS:-} ]]; then MAPS=$(cd "$MAPS" && pwd); export MAPS; fi
ARRAY=$(sbatch --parsable --array="1-$N" "$HERE/bench-shard.sbatch" "$STUDY" "$OUT")
ARRAY=${ARRAY%%;*}
MERGE=$(sbatch --parsable --dependency="afterok:$ARRAY" "$HERE/bench-merge.sbatch" "$OUT")
echo "shards: job $ARRAY (array 1-$N); merge and report: job ${MERGE%%;*}"
