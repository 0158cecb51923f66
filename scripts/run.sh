#!/usr/bin/env bash
# The main job: builds soak's command and every example, and runs the demo
# on the embedded default scene (no files needed). Plots and CSV land in
# out/demo; extra arguments go to `soak demo` (e.g. --quick, --out DIR).
#
# Two builds, each exactly what its later command builds, so that both
# `cargo run --release --example NAME` and `cargo run --release -p soak-cli`
# then start at once: the facade's examples resolve the derive macros'
# dependencies (syn and what it builds) apart from the command's, and the
# crates that use them compile twice (about 4 minutes); everything else
# the two builds share.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
if [ -z "${XDG_RUNTIME_DIR:-}" ] || [ ! -d "${XDG_RUNTIME_DIR}" ]; then
  XDG_RUNTIME_DIR="$(mktemp -d)"; chmod 700 "$XDG_RUNTIME_DIR"; export XDG_RUNTIME_DIR
fi
cargo build --release --locked -p soak --examples
cargo build --release --locked -p soak-cli
cargo run --release --locked -p soak-cli -- demo "$@"
echo "every example is built: \`cargo run --release --example NAME\` starts at once"
