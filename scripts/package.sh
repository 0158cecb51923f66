#!/usr/bin/env bash
# Packs every crate of the workspace as it would be published and checks
# that what is packed builds on its own:
# 1. `cargo package --workspace --all-features` builds each packed crate
#    from its .crate contents (every feature, the GPU kernels' WGSL included);
# 2. an empty project that depends on the packed soak-hydro with its `gpu`
#    feature (and on the packed soak-wet with its `gpu` feature), by path to
#    the unpacked .crate files, builds and runs: it composes every GPU
#    kernel's WGSL, which a crate that packed a file outside its own folder
#    would not have.
set -euo pipefail
cd "$(dirname "$0")/.."
root="$(pwd)"
# Full debug information is not needed to check that a crate builds.
export CARGO_PROFILE_DEV_DEBUG="${CARGO_PROFILE_DEV_DEBUG:-0}"
version="$(cargo metadata --format-version 1 --no-deps |
  python3 -c 'import json,sys; print(next(p["version"] for p in json.load(sys.stdin)["packages"] if p["name"] == "soak-hydro"))')"
# `cargo package --workspace` verifies each crate against the others through
# a temporary local registry, which cargo unpacks into
# $CARGO_HOME/registry/src/-<hash of its path>/ and, when a folder of the same
# name and version is already there, does not unpack again; and it takes the
# build of a registry crate of the same name and version in its target
# folder as up to date. A checkout at the same path as an earlier run would
# verify against the earlier run's sources: remove our crates' unpacked
# copies from the local registries (the folders whose name starts with '-';
# crates.io's are named after its host), and verify in a target folder of
# its own, emptied first.
cargo_home="${CARGO_HOME:-$HOME/.cargo}"
for unpacked in "$cargo_home"/registry/src/-*/soak-"$version" \
  "$cargo_home"/registry/src/-*/soak-*-"$version"; do
  if [ -d "$unpacked" ]; then rm -rf "$unpacked"; fi
done
packed="$root/target/package-verify"
rm -rf "$packed"
# The packed facade carries the workspace's profiles (deps at opt-level 2,
# Bevy at 0) and the other packed crates none: without one profile for all,
# the facade's check compiled every dependency a second time (9 of the 20
# minutes). Every check compiles its dependencies unoptimised.
CARGO_TARGET_DIR="$packed" cargo package --workspace --all-features --locked \
  --config 'profile.dev.package."*".opt-level=0'

check="$root/target/package-check"
rm -rf "$check"
mkdir -p "$check/unpacked" "$check/app/src"
for crate in "$packed"/package/*-"$version".crate; do
  tar xzf "$crate" -C "$check/unpacked"
done
patches=""
for dir in "$check"/unpacked/*/; do
  name="$(basename "$dir")"
  name="${name%-"$version"}"
  patches+="$name = { path = \"$dir\" }"$'\n'
done
cat >"$check/app/Cargo.toml" <<TOML
[package]
name = "packed-soak-check"
version = "0.0.0"
edition = "2024"
publish = false

[dependencies]
soak-hydro = { path = "$check/unpacked/soak-hydro-$version", features = ["gpu"] }
soak-wet = { path = "$check/unpacked/soak-wet-$version", features = ["gpu"] }

[patch.crates-io]
$patches
[workspace]
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
cp "$root/Cargo.lock" "$check/app/Cargo.lock"
# The same target folder as the verification above: only the packed soak
# crates build again.
CARGO_TARGET_DIR="$packed" cargo run --quiet --manifest-path "$check/app/Cargo.toml"
