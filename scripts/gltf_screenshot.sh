#!/usr/bin/env bash
# Opens a run exported by `soak simulate --gltf` in an independent viewer,
# three.js's glTF loader in headless Chromium (software WebGL), and writes a
# screenshot: the one in the README. Installs Chromium (Debian) and three
# (npm, into a temporary folder) where missing. Not part of the tests.
#
#   bash scripts/gltf_screenshot.sh [SCENE.toml] [OUT.png] [SECONDS] [WATER]
#
# SECONDS: the time into the run shown (default: the end). WATER: the level
# of the flat water drawn under the bodies, m (default 0), or "none" (a
# sea's waves are not in the file).
set -euo pipefail
cd "$(dirname "$0")/.."
scene="${1:-data/scenes/wet_crate.toml}"
out="$(realpath -m "${2:-docs/img/gltf_three.png}")"
at="${3:--1}"
water="${4:-0}"
if ! command -v chromium >/dev/null; then
  if [ "$(id -u)" -eq 0 ]; then SUDO=""; else SUDO="sudo"; fi
  echo "installing chromium" >&2
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends chromium >/dev/null
fi
command -v npm >/dev/null || { echo "needs npm (Node.js) to fetch three" >&2; exit 1; }
work="$(mktemp -d)"
server=""
cleanup() {
  [ -n "$server" ] && kill "$server" 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT
cargo build --release -p soak-cli
./target/release/soak simulate "$scene" --gltf "$work/run.glb" --out "$work/out" >/dev/null
(cd "$work" && npm install --silent --no-audit --no-fund three@0.187.0 >/dev/null)
cp scripts/gltf_view.html "$work/index.html"
port=$((20000 + RANDOM % 20000))
python3 -m http.server --bind 127.0.0.1 "$port" --directory "$work" >/dev/null 2>&1 &
server=$!
sleep 1
mkdir -p "$(dirname "$out")"
chromium --headless=new --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader \
  --hide-scrollbars --window-size=1200,787 --virtual-time-budget=30000 \
  --screenshot="$out" "http://127.0.0.1:$port/index.html?file=run.glb&t=$at&w=1200&h=787&water=$water" 2>/dev/null
if [ -n "${SOAK_GLTF_DUMP:-}" ]; then
  chromium --headless=new --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader --window-size=1200,787 \
    --virtual-time-budget=30000 --dump-dom "http://127.0.0.1:$port/index.html?file=run.glb&t=$at&w=1200&h=787&water=$water" 2>/dev/null | grep -o "<title>[^<]*"
fi
echo "wrote $out"
