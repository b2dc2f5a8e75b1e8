#!/usr/bin/env bash
# Installs what tiptap needs to build and test on Debian 12 (run as root).
set -euo pipefail
packages=(build-essential cmake pkg-config libgsl-dev libfftw3-dev libpng-dev
          libcairo2-dev libcmocka-dev fonts-dejavu-core
          libwebsockets-dev  # tiptap live: HTTP and WebSocket (docs/dependencies.md)
          python3            # the tests of tiptap live speak WebSocket and DevTools from it
          openmpi-bin libopenmpi-dev) # MPI: CI runs 'mpirun -np 2 tiptap sweep' (tests/cli_sweep.sh)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
