#!/usr/bin/env bash
# The debug job: builds the renderer and the libraries under it (core/, vdb/, image/, render/) with
# assertions on (no NDEBUG: every LH_DCHECK is checked, and OpenVDB's own asserts too) and
# runs their tests. -O1 keeps the suite at CI speed; the network is left out (libtorch's
# headers dominate a debug build and its tests run in the release job).
# Output: build-debug/ (reused on the next run).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=${JOBS:-2}
cmake -S . -B build-debug -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-g -O1" \
  -DLIGHTHOUSE_WITH_TORCH=OFF -DLIGHTHOUSE_BUILD_BENCH=OFF >/dev/null
cmake --build build-debug -- -j"$jobs" core_tests vdb_tests vdb_envmap_tests image_tests render_tests
for suite in core_tests vdb_tests vdb_envmap_tests image_tests render_tests; do
  echo "==> $suite (debug, LH_DCHECK on)"
  build-debug/tests/$suite --gtest_brief=1
done
echo "==> debug job: core, vdb, image and render tests passed with LH_DCHECK on"
