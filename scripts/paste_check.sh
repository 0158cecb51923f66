#!/usr/bin/env bash
# The README's Rapier program, pasted as src/main.rs into a new project
# that depends on soak by path (without its default features, as the
# README says a library takes it) and on rapier3d, builds in release and
# runs.
set -euo pipefail
cd "$(dirname "$0")/.."
root="$(pwd)"
app="$root/target/paste-check"
rm -rf "$app"
mkdir -p "$app/src"
python3 - "$root/README.md" "$app/src/main.rs" <<'PY'
import sys
readme = open(sys.argv[1]).read()
start = readme.index("```rust\n") + len("```rust\n")
open(sys.argv[2], "w").write(readme[start:readme.index("```", start)])
PY
rapier="$(sed -n 's/^rapier3d = { *version = "\([^"]*\)".*/\1/p; s/^rapier3d = "\([^"]*\)"/\1/p' "$root/Cargo.toml" | head -1)"
cat >"$app/Cargo.toml" <<TOML
[package]
name = "pasted"
version = "0.0.0"
edition = "2024"
publish = false

[dependencies]
soak = { path = "$root", default-features = false }
rapier3d = "$rapier"

[workspace]
TOML
# The workspace's lock file pins the same versions of every dependency.
cp "$root/Cargo.lock" "$app/Cargo.lock"
out="$(CARGO_TARGET_DIR="$root/target" cargo run --quiet --release --manifest-path "$app/Cargo.toml")"
echo "$out"
case "$out" in
  *"the boat floats"*) ;;
  *) echo "the pasted README program printed no draft" >&2; exit 1 ;;
esac
