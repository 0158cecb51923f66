#!/usr/bin/env bash
# The viewer's long run: `soak view` on the busy scene of
# scripts/long_run/busy.toml under Xvfb (default: an hour of wall time; it
# closes itself with --seconds), its resident memory sampled every minute.
# Prints the memory at each minute, then the viewer's own summary (frames,
# step time, simulated time), what its CSV holds (scripts/long_run/ledger.py:
# rows, any value that is not finite, speed, height and the liquid ledgers)
# and where it wrote its last frame.
#   bash scripts/long_view.sh [MINUTES]
set -euo pipefail
cd "$(dirname "$0")/.."
minutes=${1:-60}
command -v xvfb-run > /dev/null || { echo "long_view.sh needs xvfb-run (Debian: xvfb)" >&2; exit 1; }
cargo build --release -p soak-cli -q
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
export XDG_RUNTIME_DIR="$dir/runtime"
mkdir -m 700 "$XDG_RUNTIME_DIR"
xvfb-run -a -s "-screen 0 1280x720x24" target/release/soak view scripts/long_run/busy.toml \
  --seconds $((minutes * 60)) --screenshot "$dir/last.png" --csv "$dir/view.csv" > "$dir/out.txt" 2> "$dir/err.txt" &
runner=$!
sleep 20
pid=$(pgrep -n -x soak || true)
for minute in $(seq 0 "$minutes"); do
  if [ -z "$pid" ] || ! kill -0 "$pid" 2> /dev/null; then
    echo "the viewer closed before minute $minute"
    break
  fi
  echo "minute $minute: resident $(awk '/VmRSS/ {print $2, $3}' "/proc/$pid/status")"
  sleep 60
done
wait "$runner" || true
cat "$dir/out.txt" "$dir/err.txt"
python3 scripts/long_run/ledger.py "$dir/view.csv"
cp "$dir/last.png" long_view_last.png 2> /dev/null && echo "last frame: long_view_last.png" || true
