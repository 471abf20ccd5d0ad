#!/usr/bin/env bash
# Configures and builds everything (libraries, the `lighthouse` CLI, tests, benchmarks) into
# build/ with CMake + Ninja, two jobs (the machine has two cores).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build -- -j2
