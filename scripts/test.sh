#!/usr/bin/env bash
# Everything CI does: system packages the tests need, formatting, lints, tests
# (GPU tests included: they run on Mesa's software adapters, and fail under
# CI=true when no adapter is found).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
if [ -z "${XDG_RUNTIME_DIR:-}" ] || [ ! -d "${XDG_RUNTIME_DIR}" ]; then
  XDG_RUNTIME_DIR="$(mktemp -d)"
  chmod 700 "$XDG_RUNTIME_DIR"
  export XDG_RUNTIME_DIR
fi
# A one-off build gains nothing from incremental artefacts (gigabytes on disk).
export CARGO_INCREMENTAL="${CARGO_INCREMENTAL:-0}"
# Each stage's start, for seeing where the time goes.
stage() { echo "== $(date -u +%H:%M:%S) $*"; }
stage fmt
cargo fmt --all -- --check
# No file of a crate imports another that imports it back.
python3 scripts/module_cycles.py crates/*/src
stage clippy
cargo clippy --workspace --all-targets --all-features --locked -- -D warnings
# Every crate packed as it would be published compiles on its own, the GPU
# kernels of the packed crates included (checked in the same target folder
# as clippy's: its dependencies are not compiled again).
stage package
bash scripts/package.sh
# The fuzz targets are their own workspace (fuzz/); they must build, on
# stable, without cargo-fuzz or nightly (docs/fuzzing.md runs them).
stage fuzz
cargo fmt --manifest-path fuzz/Cargo.toml -- --check
cargo clippy --manifest-path fuzz/Cargo.toml --all-targets --locked -- -D warnings
stage test
cargo test --workspace --all-features --locked
# The API documentation builds without a warning (intra-doc links resolve).
stage doc
RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps --all-features --locked
# The README's program, pasted into a new project, builds and runs.
stage paste
bash scripts/paste_check.sh
stage done
# Disk used by the build, for keeping CI within its machine.
du -sh target fuzz/target 2>/dev/null || true
