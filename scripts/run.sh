#!/usr/bin/env bash
# The main job: builds soak's command and every example in one build (the
# facade's default features are the command's: one resolution of the
# dependencies serves both, so `cargo run --release --example NAME` then
# starts at once), and runs the demo on the embedded default scene (no
# files needed). Plots and CSV land in out/demo; extra arguments go to
# `soak demo` (e.g. --quick, --out DIR).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
if [ -z "${XDG_RUNTIME_DIR:-}" ] || [ ! -d "${XDG_RUNTIME_DIR}" ]; then
  XDG_RUNTIME_DIR="$(mktemp -d)"; chmod 700 "$XDG_RUNTIME_DIR"; export XDG_RUNTIME_DIR
fi
cargo build --release --locked -p soak-cli -p soak --bins --examples
cargo run --release --locked -p soak-cli -- demo "$@"
echo "every example is built: \`cargo run --release --example NAME\` starts at once"
