#!/usr/bin/env bash
# Installs the Debian 12 packages Lighthouse-VDB builds and tests with (listed below).
# Needs root, or sudo. Safe to run again.
set -euo pipefail

packages=(
  g++ cmake ninja-build pkg-config
  libopenvdb-dev libopenvdb-tools libnanovdb-dev libboost-iostreams-dev libblosc-dev
  libtbb-dev libopenexr-dev libimath-dev libcli11-dev nlohmann-json3-dev libstb-dev
  libgtest-dev libbenchmark-dev
  libembree-dev                   # ray casting: synthetic scenes, inserted objects
  libtinyobjloader-dev            # OBJ meshes of inserted objects
  libexif-dev                     # EXIF focal lengths of real photos (lighthouse cameras --exif)
  libtorch-dev                    # the prediction network (net/), CPU build
  libgloo-dev                     # headers of Gloo, which libtorch's c10d uses for data-parallel training (net/distributed.cpp)
  libopenblas0-pthread            # fast BLAS for libtorch (the reference BLAS is ~50x slower)
  python3-openvdb python3-numpy   # interop tests: files read and written by python3-openvdb
  blender                         # DCC round trip: Cycles renders of `lighthouse export` (tests/python/dcc_blender_cycles.py)
  slurm-wlm munge                 # batch jobs on Slurm: scripts/slurm/, tested on a one-node cluster (tests/slurm/)
  colmap                          # optional for users: lighthouse cameras --photos (docs/cameras.md); its tests run when it is here
)

run() { if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi; }

export DEBIAN_FRONTEND=noninteractive
echo "==> apt-get update"
run apt-get update -q
echo "==> installing ${#packages[@]} packages"
run apt-get install -y -q --no-install-recommends "${packages[@]}"
