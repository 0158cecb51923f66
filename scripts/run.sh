#!/usr/bin/env bash
# The main job: builds soak and runs its demo on the embedded default scene
# (no files needed). Plots and CSV land in out/demo; extra arguments go to
# `soak demo` (e.g. --quick, --out DIR). Then builds the examples as
# `cargo run --release --example NAME` builds them (the facade's default
# features: the command-line tool's GPU and renderer features resolve its
# dependencies differently), so that each of them starts at once.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
if [ -z "${XDG_RUNTIME_DIR:-}" ] || [ ! -d "${XDG_RUNTIME_DIR}" ]; then
  XDG_RUNTIME_DIR="$(mktemp -d)"; chmod 700 "$XDG_RUNTIME_DIR"; export XDG_RUNTIME_DIR
fi
cargo run --release --locked -p soak-cli -- demo "$@"
echo "building the examples: \`cargo run --release --example NAME\` then starts without a build"
cargo build --release --locked --examples
