#!/usr/bin/env bash
# Times the `soak bench` world in Jolt Physics (scripts/references/jolt_floating.cpp)
# for a side-by-side comparison with `soak bench`.
#
#   scripts/jolt_bench.sh JOLT_CHECKOUT [harness arguments...]
#
# JOLT_CHECKOUT is a checkout of github.com/jrouwe/JoltPhysics (its `Jolt`
# folder is what is built: every source compiled with g++ -O3
# -march=native, no CMake needed). The harness arguments are those of
# jolt_floating.cpp: [N] [--threads T] [--steps S] [--spheres] [--analytic].
# The objects and the library are kept in target/jolt, so a second run
# builds nothing (remove that folder after changing the checkout). Compare with, on the same machine and at the same time:
#
#   RAYON_NUM_THREADS=1 soak bench --sizes 1000 --water calm --interleave --drag-coarsening 4
set -euo pipefail

if [[ $# -lt 1 || ! -d "$1/Jolt" ]]; then
    echo "usage: $0 JOLT_CHECKOUT [N] [--threads T] [--steps S] [--spheres] [--analytic]" >&2
    exit 2
fi
jolt=$(cd "$1" && pwd)
shift
root=$(cd "$(dirname "$0")/.." && pwd)
out="$root/target/jolt"
mkdir -p "$out/obj"
# One set of flags for the library and the harness.
export JOLT_DIR="$jolt" JOLT_OUT="$out" JOLT_CXXFLAGS="-O3 -march=native -DNDEBUG -std=c++17"

# The library, one object per source, two at a time.
(cd "$jolt" && find Jolt -name '*.cpp') | xargs -r -P 2 -I{} sh -c \
    'o="$JOLT_OUT/obj/$(echo {} | tr / _).o"; [ -f "$o" ] ||
     g++ $JOLT_CXXFLAGS -I"$JOLT_DIR" -w -c "$JOLT_DIR/{}" -o "$o"'
rm -f "$out/libJolt.a"
ar rcs "$out/libJolt.a" "$out"/obj/*.o

# shellcheck disable=SC2086 # the flags are words
g++ $JOLT_CXXFLAGS -I"$jolt" "$root/scripts/references/jolt_floating.cpp" "$out/libJolt.a" -lpthread -o "$out/jolt_floating"
exec "$out/jolt_floating" "$@"
