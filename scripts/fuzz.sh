#!/usr/bin/env bash
# Run every fuzz target for SECONDS each (default 60), one after another:
#
#   scripts/fuzz.sh [SECONDS] [TARGET...]
#   FUZZ_RUNS=1000000 scripts/fuzz.sh 7200 png    # stop each after a million executions
#
# Needs a nightly toolchain and cargo-fuzz (`cargo install cargo-fuzz`). Each target starts
# from its committed seeds (fuzz/seeds/TARGET) plus what earlier runs found
# (fuzz/corpus/TARGET, not committed); its log goes to fuzz/logs/TARGET.log. A crash stops
# that target with the input in fuzz/artifacts/TARGET. The number of executions of each
# target is printed at the end, and the script fails if any target crashed. An input may
# take 10 s and 2 GB: more is reported as a crash (an unbounded allocation or a hang on bad
# input is a bug).
set -euo pipefail
cd "$(dirname "$0")/.."
# Targets that read files get them written per input: in memory, where there is room, in a
# folder of this run's that is removed at the end (a fuzzer stopped by its time limit
# leaves its own folder behind).
base=${TMPDIR:-}
if [[ -z "$base" && -d /dev/shm && -w /dev/shm ]]; then base=/dev/shm; fi
TMPDIR=$(mktemp -d "${base:-/tmp}/frontier-fuzz-run.XXXXXX")
export TMPDIR
trap 'rm -rf "$TMPDIR"' EXIT
SECONDS_EACH=${1:-60}
shift || true
if (($# > 0)); then TARGETS=("$@"); else mapfile -t TARGETS < <(cargo +nightly fuzz list --fuzz-dir fuzz); fi
cargo +nightly fuzz build --fuzz-dir fuzz -O
summary=()
for t in "${TARGETS[@]}"; do
  mkdir -p "fuzz/corpus/$t" "fuzz/artifacts/$t" fuzz/logs
  log=fuzz/logs/$t.log
  echo "fuzzing $t for ${SECONDS_EACH}s" >&2
  rc=0
  cargo +nightly fuzz run --fuzz-dir fuzz -O "$t" "fuzz/corpus/$t" "fuzz/seeds/$t" -- \
    -max_total_time="$SECONDS_EACH" -timeout=10 -rss_limit_mb=2048 -max_len=8192 \
    -print_final_stats=1 ${FUZZ_RUNS:+-runs="$FUZZ_RUNS"} >"$log" 2>&1 || rc=$?
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
  if ((rc != 0)); then
    summary+=("$t: FAILED after $execs executions (exit $rc); see $log")
  else
    summary+=("$t: $execs executions, no crash")
  fi
done
printf '%s\n' "${summary[@]}"
! printf '%s\n' "${summary[@]}" | grep -q FAILED
