#!/usr/bin/env bash
# Installs what tiptap needs to build and test on Debian 12 (run as root).
set -euo pipefail
packages=(build-essential cmake pkg-config libgsl-dev libfftw3-dev libpng-dev
          zlib1g-dev                 # the previews' PNGs deflated directly (src/io/png_encode.c)
          libcairo2-dev libcmocka-dev fonts-dejavu-core
          openmpi-bin libopenmpi-dev # MPI: CI runs 'mpirun -np 2 tiptap sweep' (tests/cli_sweep.sh)
          libhdf5-dev                # scan --hdf5, sweep --hdf5 (docs/hdf5.md)
          libwebsockets-dev          # tiptap live: HTTP and WebSocket (docs/dependencies.md)
          # python3: the live tests' WebSocket and DevTools clients; the Python package and
          # its tests (docs/python.md), for /usr/bin/python3; pip and setuptools for the
          # test of `pip install ./python` without a download
          python3 python3-numpy python3-cffi python3-pytest python3-h5py
          python3-pip python3-setuptools)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
