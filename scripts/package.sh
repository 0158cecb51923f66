#!/usr/bin/env bash
# Packs every crate of the workspace as it would be published and checks
# that what is packed compiles:
# 1. `cargo package --workspace --no-verify` packs each crate;
# 2. the packed crates, unpacked, are the members of a workspace of their
#    own (each other's dependencies through `[patch.crates-io]`, as they
#    would be from the registry), checked with every feature: a file a
#    crate includes from outside its folder (a GPU kernel's WGSL, a scene,
#    a shader) or a module it does not pack fails the check.
# The check workspace carries the main workspace's profiles and checks in
# its target folder, after clippy: the dependencies are not compiled again.
# Not checked: each crate's features resolved alone. `cargo package`'s own
# verification checked that too, building each crate on its own, at the
# cost of ~700 crates compiled a second time (14 of CI's minutes; each
# crate checked on its own, 9).
set -euo pipefail
cd "$(dirname "$0")/.."
root="$(pwd)"
version="$(cargo metadata --format-version 1 --no-deps |
  python3 -c 'import json,sys; print(next(p["version"] for p in json.load(sys.stdin)["packages"] if p["name"] == "soak-hydro"))')"
cargo package --workspace --no-verify --locked --quiet ${SOAK_PACKAGE_ALLOW_DIRTY:+--allow-dirty}

check="$root/target/package-check"
rm -rf "$check"
mkdir -p "$check/unpacked"
crates=()
for crate in "$root"/target/package/*-"$version".crate; do
  tar xzf "$crate" -C "$check/unpacked"
  name="$(basename "$crate" .crate)"
  crates+=("${name%-"$version"}")
done
# A path crate counts as up to date when its files are older than its last
# build: the files keep the times they were packed with, so a later pack of
# changed sources with older times would be taken as built. Touched, they
# are newer than any earlier build.
find "$check/unpacked" -type f -exec touch {} +
patches=""
for name in "${crates[@]}"; do
  patches+="$name = { path = \"unpacked/$name-$version\" }"$'\n'
done
{
  cat <<TOML
[workspace]
resolver = "3"
members = ["unpacked/*"]

[patch.crates-io]
$patches
TOML
  # The main workspace's profiles, so that the dependencies' builds are the
  # same builds.
  sed -n '/^\[profile\./,$p' "$root/Cargo.toml"
} >"$check/Cargo.toml"
# The workspace's lock file pins the same versions of every dependency.
cp "$root/Cargo.lock" "$check/Cargo.lock"
CARGO_TARGET_DIR="$root/target" cargo check --quiet --manifest-path "$check/Cargo.toml" --workspace --all-features
echo "the ${#crates[@]} packed crates compile"
