#!/usr/bin/env bash
# One long run of `soak simulate` (default: an hour of wall time) on the busy
# scene of scripts/long_run/busy.toml, its resident memory sampled every
# minute, then stopped with Ctrl-C (it writes its checkpoint and says where
# it stopped). Prints the memory at each minute and what the CSV holds at
# the end: rows, any value that is not finite, the liquid ledgers.
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
python3 - "$dir/busy.csv" <<'PY'
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
bodies = {}
for r in rows:
    bodies.setdefault(r["body"], []).append(r)
for name, rs in bodies.items():
    bad = sum(1 for r in rs for k, v in r.items() if k != "body" and not math.isfinite(float(v)))
    soaked = [1e3 * float(r["surface_liquid_m3"]) for r in rs]
    inside = [float(r["liquid_inside_m3"]) for r in rs]
    half = len(rs) // 2
    print(f"{name}: {len(rs)} rows to t = {rs[-1]['t_s']} s, {bad} not finite; "
          f"soaked {min(soaked[half:]):.2f}–{max(soaked[half:]):.2f} L over the second half; "
          f"inside at most {max(inside):.3f} m³")
PY
