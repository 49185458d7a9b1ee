#!/usr/bin/env bash
# Installs subfab's build and test dependencies from Debian 12 packages.
# Idempotent: checks what is missing first, runs `apt-get update` once and
# `apt-get install -y` only for the missing packages. Nothing is downloaded
# from anywhere else, nothing is vendored.
set -euo pipefail

packages=(
  build-essential cmake make pkg-config ccache python3
  libcgal-dev libgmp-dev libmpfr-dev
  libeigen3-dev
  libboost-dev libboost-graph-dev
  coinor-libcbc-dev coinor-libclp-dev coinor-libcgl-dev coinor-libosi-dev coinor-libcoinutils-dev
  libtbb-dev
  libcli11-dev
  nlohmann-json3-dev
  libgtest-dev libgmock-dev
  zlib1g-dev
  # 3MF input: libzip opens the zip, expat parses 3D/3dmodel.model.
  libzip-dev libexpat1-dev
  # view.html inlines three.js; the browser tests of view.html and
  # assembly.html run headless Debian chromium (skipped when it is missing).
  libjs-three chromium chromium-driver
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all dependencies present"
  exit 0
fi

echo "setup: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then SUDO="sudo"; else
    echo "setup: need root (or sudo) to install: ${missing[*]}" >&2; exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
echo "setup: done"
