#!/usr/bin/env bash
# Packs every crate of the workspace as it would be published and checks
# that what is packed compiles on its own:
# 1. `cargo package --workspace --no-verify` packs each crate;
# 2. the packed crates, unpacked, are the members of a workspace of their
#    own (each other's dependencies through `[patch.crates-io]`, as they
#    would be from the registry), and each is checked alone with every
#    feature (`cargo check -p CRATE --all-features`: its own features
#    resolved, as a user's build would; a file it includes from outside its
#    folder, such as a GPU kernel's WGSL, fails the check);
# 3. a small program of that workspace, depending on the packed soak-hydro
#    and soak-wet with their `gpu` feature, builds and runs: it composes
#    every GPU kernel's WGSL.
# The check workspace carries the main workspace's profiles and builds in
# its target folder, so the dependencies clippy checked and the tests build
# are not compiled again (`cargo package`'s own verification compiled ~700
# crates a second time, unoptimised: 14 of CI's minutes).
set -euo pipefail
cd "$(dirname "$0")/.."
root="$(pwd)"
version="$(cargo metadata --format-version 1 --no-deps |
  python3 -c 'import json,sys; print(next(p["version"] for p in json.load(sys.stdin)["packages"] if p["name"] == "soak-hydro"))')"
cargo package --workspace --no-verify --locked --quiet ${SOAK_PACKAGE_ALLOW_DIRTY:+--allow-dirty}

check="$root/target/package-check"
rm -rf "$check"
mkdir -p "$check/unpacked" "$check/app/src"
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
members = ["unpacked/*", "app"]

[patch.crates-io]
$patches
TOML
  # The main workspace's profiles, so that the dependencies' builds are the
  # same builds.
  sed -n '/^\[profile\./,$p' "$root/Cargo.toml"
} >"$check/Cargo.toml"
cat >"$check/app/Cargo.toml" <<TOML
[package]
name = "packed-soak-check"
version = "0.0.0"
edition = "2024"
publish = false

[dependencies]
soak-hydro = { version = "$version", features = ["gpu"] }
soak-wet = { version = "$version", features = ["gpu"] }
TOML
cat >"$check/app/src/main.rs" <<'RS'
//! Composes every GPU kernel of the packed crates: each must be non-empty
//! WGSL with an entry point.
fn main() {
    let kernels: Vec<(&str, String)> = soak_hydro::gpu::kernel_sources()
        .into_iter()
        .chain(soak_wet::gpu::kernel_sources())
        .collect();
    for (name, source) in &kernels {
        assert!(source.contains("fn main"), "kernel {name} has no entry point");
    }
    println!("{} kernels composed from the packed crates", kernels.len());
}
RS
# The workspace's lock file pins the same versions of every dependency.
cp "$root/Cargo.lock" "$check/Cargo.lock"
export CARGO_TARGET_DIR="$root/target"
for name in "${crates[@]}"; do
  echo "$(date -u +%H:%M:%S) checking the packed $name"
  cargo check --quiet --manifest-path "$check/Cargo.toml" -p "$name" --all-features
done
cargo run --quiet --manifest-path "$check/Cargo.toml" -p packed-soak-check
