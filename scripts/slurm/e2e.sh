#!/usr/bin/env bash
# End-to-end test of the Slurm scripts on a real one-node cluster on this machine.
#
#   scripts/slurm/e2e.sh [STUDY] [N]       (defaults: quick 4)
#
# Installs Debian's slurm-wlm and munge if missing (needs root and apt-get), starts a private
# munged, slurmctld and slurmd from a minimal slurm.conf in a temporary directory, submits
# STUDY as N shards plus the merge job with scripts/slurm/submit.sh, waits for the merge, and
# checks that the merged database holds exactly the trials of an unsharded `frontier bench`
# run (every column but the wall time) and that the report was written. The daemons it
# started are stopped on exit, whatever happens. FRONTIER may name the binary to test
# (default: a release build of this checkout); KEEP=1 keeps the temporary directory; MAPS
# names the folder of a map-folder suite (MAPS=maps/ scripts/slurm/e2e.sh holz2010-real).
set -euo pipefail
if [[ -n ${MAPS:-} ]]; then MAPS=$(cd "$MAPS" && pwd); export MAPS; fi
cd "$(dirname "$0")/../.."
ROOT=$(pwd)
STUDY=${1:-quick}
N=${2:-4}
started=$(date +%s)
say() { echo "slurm-e2e: $*" >&2; }
fail() { say "FAIL: $*"; exit 1; }

if ! command -v slurmctld >/dev/null 2>&1 || ! command -v slurmd >/dev/null 2>&1 \
  || ! command -v sbatch >/dev/null 2>&1 || ! command -v munged >/dev/null 2>&1; then
  say "installing slurm-wlm and munge"
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends slurm-wlm munge
fi
command -v python3 >/dev/null 2>&1 || fail "python3 is needed to compare the databases"

if [[ -z ${FRONTIER:-} ]]; then
  cargo build --release -p frontier
  FRONTIER=$ROOT/target/release/frontier
fi
export FRONTIER
[[ -x $FRONTIER ]] || fail "no frontier binary at $FRONTIER"

T=$(mktemp -d "${TMPDIR:-/tmp}/frontier-slurm-e2e.XXXXXX")
chmod 755 "$T"
PIDS=()
cleanup() {
  local rc=$?
  if [[ -n ${SLURM_CONF:-} ]] && ((${#PIDS[@]} > 1)); then
    scancel --quiet --user "$(id -un)" 2>/dev/null || true
  fi
  # Stop the daemons this script started, newest first, by their process ids.
  for ((i = ${#PIDS[@]} - 1; i >= 0; i--)); do
    kill "${PIDS[i]}" 2>/dev/null || true
  done
  for pid in "${PIDS[@]}"; do
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$pid" 2>/dev/null || true
  done
  if ((rc != 0)); then
    for log in "$T"/*.log "$T"/jobs/*.out; do
      [[ -f $log ]] && { say "--- $log"; tail -n 20 "$log" >&2; }
    done
  fi
  if [[ ${KEEP:-0} == 1 ]]; then say "kept $T"; else rm -rf "$T"; fi
  exit "$rc"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

# munge: a private key, socket and daemon (an already running munged is left alone).
mkdir -p "$T/munge"
chmod 700 "$T/munge"
mungekey --create --keyfile="$T/munge/munge.key" 2>/dev/null \
  || dd if=/dev/urandom of="$T/munge/munge.key" bs=1 count=1024 status=none
chmod 600 "$T/munge/munge.key"
SOCKET=$T/munge/munge.socket
munged --foreground --force --key-file="$T/munge/munge.key" --socket="$SOCKET" \
  --pid-file="$T/munge/munged.pid" --log-file="$T/munged.log" \
  --seed-file="$T/munge/munged.seed" >"$T/munged.out.log" 2>&1 &
PIDS+=($!)
for _ in $(seq 100); do [[ -S $SOCKET ]] && break; sleep 0.1; done
[[ -S $SOCKET ]] || fail "munged did not start"
munge --socket="$SOCKET" -n | unmunge --socket="$SOCKET" >/dev/null || fail "munge does not round-trip"

# A one-node cluster: this machine, with enough CPUs configured for the shard jobs'
# --cpus-per-task (config_overrides: slurmd trusts slurm.conf over the hardware).
NODE=$(hostname -s)
USER_NAME=$(id -un)
CPUS=16
PORT=${SLURM_E2E_PORT:-16817}
mkdir -p "$T/state" "$T/spool" "$T/jobs"
cat >"$T/slurm.conf" <<EOF
ClusterName=frontier-e2e
SlurmctldHost=$NODE(127.0.0.1)
SlurmUser=$USER_NAME
SlurmdUser=$USER_NAME
SlurmctldPort=$PORT
SlurmdPort=$((PORT + 1))
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$SOCKET
StateSaveLocation=$T/state
SlurmdSpoolDir=$T/spool/%n
SlurmctldPidFile=$T/slurmctld.pid
SlurmdPidFile=$T/slurmd.pid
SlurmctldLogFile=$T/slurmctld.log
SlurmdLogFile=$T/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SwitchType=switch/none
MpiDefault=none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SlurmdParameters=config_overrides
ReturnToService=2
MinJobAge=3600
NodeName=$NODE NodeAddr=127.0.0.1 CPUs=$CPUS State=UNKNOWN
PartitionName=e2e Nodes=$NODE Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$T/slurm.conf
slurmctld -D -f "$SLURM_CONF" >"$T/slurmctld.out.log" 2>&1 &
PIDS+=($!)
slurmd -D -f "$SLURM_CONF" -N "$NODE" >"$T/slurmd.out.log" 2>&1 &
PIDS+=($!)
state=
for _ in $(seq 120); do
  state=$(sinfo -h -n "$NODE" -o %T 2>/dev/null || true)
  [[ $state == idle ]] && break
  sleep 0.5
done
[[ $state == idle ]] || fail "node $NODE is '$state', not idle, after 60 s"
say "cluster up ($NODE, $CPUS CPUs); submitting $STUDY as $N shards"

OUT=$T/jobs/out
cd "$T/jobs"
submitted=$("$ROOT/scripts/slurm/submit.sh" "$STUDY" "$OUT" "$N")
echo "$submitted"
MERGE=${submitted##*job }
[[ $MERGE =~ ^[0-9]+$ ]] || fail "no merge job id in: $submitted"

# Wait for the merge job (it runs once every shard has succeeded).
job_state() { scontrol show job "$1" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p'; }
while :; do
  s=$(job_state "$MERGE")
  case $s in
    COMPLETED) break ;;
    PENDING | RUNNING | CONFIGURING | COMPLETING) sleep 2 ;;
    *) scontrol show job "$MERGE" >&2 || true; fail "merge job $MERGE ended as '$s'" ;;
  esac
  (($(date +%s) - started < 3600)) || fail "merge job $MERGE not done after an hour"
done
cd "$ROOT"
shards=("$OUT"/shard-*-of-"$N".sqlite)
((${#shards[@]} == N)) || fail "expected $N shard databases, found ${#shards[@]}"
[[ -s $OUT/all.sqlite ]] || fail "no merged database"
[[ -s $OUT/report/report.html ]] || fail "no report.html"
say "merge job $MERGE done; running $STUDY unsharded for comparison"

"$FRONTIER" bench --suite "$STUDY" ${MAPS:+--maps "$MAPS"} --db "$T/unsharded.sqlite" --no-progress
"$FRONTIER" bench export "$T/unsharded.sqlite" --csv "$T/unsharded.csv" >/dev/null
"$FRONTIER" bench export "$OUT/all.sqlite" --csv "$T/merged.csv" >/dev/null
python3 - "$T/unsharded.csv" "$T/merged.csv" <<'EOF'
import csv, sys

def rows(path):
    with open(path, newline="") as f:
        out = {}
        for r in csv.DictReader(f):
            r.pop("wall_s")
            out[r["key"]] = r
        return out

whole, merged = rows(sys.argv[1]), rows(sys.argv[2])
missing = sorted(whole.keys() - merged.keys())
extra = sorted(merged.keys() - whole.keys())
differ = sorted(k for k in whole.keys() & merged.keys() if whole[k] != merged[k])
for what, keys in (("missing from the merge", missing), ("only in the merge", extra), ("different", differ)):
    if keys:
        print(f"{len(keys)} trial(s) {what}, e.g. {keys[0]}", file=sys.stderr)
if missing or extra or differ or not whole:
    sys.exit(1)
print(f"slurm-e2e: merged database = unsharded run: {len(whole)} trials", file=sys.stderr)
EOF
say "PASS in $(($(date +%s) - started)) s"
