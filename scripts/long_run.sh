#!/usr/bin/env bash
# One long run of `soak simulate` (default: an hour of wall time) on the busy
# scene of scripts/long_run/busy.toml, its resident memory sampled every
# minute, then stopped with Ctrl-C (it writes its checkpoint and says where
# it stopped). Prints the memory at each minute and what the CSV holds at
# the end (scripts/long_run/ledger.py): rows, any value that is not finite,
# speed, height and the liquid ledgers.
#   bash scripts/long_run.sh [MINUTES]
set -euo pipefail
cd "$(dirname "$0")/.."
minutes=${1:-60}
cargo build --release -p soak-cli -q
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
target/release/soak simulate scripts/long_run/busy.toml --csv "$dir/busy.csv" \
  --checkpoint "$dir/busy.ckpt" --checkpoint-every 600 > "$dir/out.txt" 2> "$dir/err.txt" &
pid=$!
for minute in $(seq 1 "$minutes"); do
  sleep 60
  echo "minute $minute: resident $(awk '/VmRSS/ {print $2, $3}' "/proc/$pid/status")"
done
kill -INT "$pid"
wait "$pid" || true
tail -6 "$dir/out.txt"
python3 scripts/long_run/ledger.py "$dir/busy.csv"
