#!/usr/bin/env bash
# Frame and step times of `soak view` on a virtual X server (Xvfb), for the
# scenes shipped with soak and for `data/scenes/slow_crates.toml` (about ten
# times slower than real time), the latter with mouse drags sent by
# xdotool: the time from an input to the frame that shows it. On a machine
# without a GPU the frames are drawn by Mesa's software adapter: the times
# are those of the CPU rasteriser, not of a GPU.
#
#   bash scripts/view_times.sh [SECONDS] [WIDTH] [HEIGHT]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
seconds="${1:-8}"
width="${2:-960}"
height="${3:-540}"
cargo build --release -p soak-cli
if [ -z "${XDG_RUNTIME_DIR:-}" ] || [ ! -d "${XDG_RUNTIME_DIR}" ]; then
  XDG_RUNTIME_DIR="$(mktemp -d)"
  chmod 700 "$XDG_RUNTIME_DIR"
  export XDG_RUNTIME_DIR
fi
soak="$PWD/target/release/soak"
for name in buoy_on_waves sinking_boat three_boxes wet_crate rain_and_splash; do
  echo "demo:$name"
  xvfb-run -a -s "-screen 0 1280x1024x24" "$soak" view "demo:$name" --seconds "$seconds" --width "$width" --height "$height" | tail -n 1
done
echo "data/scenes/slow_crates.toml, dragged with the mouse"
xvfb-run -a -s "-screen 0 1280x1024x24" sh -c "
  \"$soak\" view data/scenes/slow_crates.toml --seconds $((seconds + 4)) --width $width --height $height & pid=\$!
  sleep 4; xdotool mousemove $((width / 2)) $((height / 2))
  for i in \$(seq 1 $((seconds * 2))); do
    xdotool mousedown 1; sleep 0.05; xdotool mousemove_relative 12 2; sleep 0.2; xdotool mouseup 1; sleep 0.2
  done
  wait \$pid" | tail -n 1
