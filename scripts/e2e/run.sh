#!/usr/bin/env bash
# End-to-end test of the replay page in a real headless browser.
# Installs Debian's chromium (if missing) and playwright-core (npm, pinned), writes a replay
# of a single-robot run, a two-robot run and a segmenting run, and checks each page against the run's JSON
# summary. Screenshots go to target/e2e/.
set -euo pipefail
cd "$(dirname "$0")/../.."
if ! command -v chromium >/dev/null 2>&1; then
  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium
fi
(cd scripts/e2e && npm install --no-audit --no-fund --silent)
cargo build --release -p frontier
out=target/e2e
mkdir -p "$out"
run() {
  local name=$1; shift
  ./target/release/frontier explore "$@" --html "$out/$name.html" --json --no-timing > "$out/$name.json"
  REPLAY_HTML="$out/$name.html" REPLAY_JSON="$out/$name.json" SCREENSHOT="$out/$name.png" \
    node --test scripts/e2e/replay.test.mjs
}
run hospital --env hospital --seed 2 --strategy cf-rr
run office-team --env office --seed 1 --strategy cf-rr --robots 2
run office-seg --env office --seed 1 --strategy cf-rr-seg
echo "screenshots in $out/"
