#!/usr/bin/env bash
# Installs the system packages soak needs on a Debian machine (idempotent):
# Mesa's software Vulkan (lavapipe) and GL (llvmpipe) drivers, so the wgpu
# code runs headless without a GPU; a virtual X server (Xvfb, with xauth
# for xvfb-run) and xdotool, so the tests open `soak view`'s window and
# drive it with the mouse.
set -euo pipefail
packages=(mesa-vulkan-drivers libvulkan1 libegl1 libegl-mesa0 libgl1-mesa-dri xvfb xauth xdotool)
need=()
for pkg in "${packages[@]}"; do
  dpkg -s "$pkg" >/dev/null 2>&1 || need+=("$pkg")
done
if [ ${#need[@]} -gt 0 ]; then
  if [ "$(id -u)" -eq 0 ]; then SUDO=""; else SUDO="sudo"; fi
  echo "installing ${need[*]}" >&2
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${need[@]}" >/dev/null
fi
command -v cargo >/dev/null || { echo "soak needs a Rust toolchain (https://rustup.rs)" >&2; exit 1; }
