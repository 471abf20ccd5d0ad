#!/usr/bin/env bash
# Memory against envmap error (issue 7, "storing only what the scene needs"): runs
# `lighthouse bench-sparsity` on an oracle volume of a synthetic room (with its ground-truth
# envmaps, so the PSNR lost against ground truth is measured) and on the bundled example room.
# Predicted volumes: pass any .vdb as the third argument once the network writes them.
#
#   bash scripts/sparsity_study.sh [OUT] [EXAMPLE_DIR] [EXTRA.vdb]
#     OUT          default out/sparsity
#     EXAMPLE_DIR  a synthetic example (cameras.json + env_*.exr); default: made with
#                  `lighthouse synth --split test --seed 0 --count 2` under OUT/test
#
# Writes OUT/<name>/memory_error.{csv,md,svg} and prints the tables.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${LIGHTHOUSE:-build/cli/lighthouse}
out=${1:-out/sparsity}
example=${2:-}
extra=${3:-}
mkdir -p "$out"
if [ -z "$example" ]; then
  [ -f "$out/test/manifest.json" ] || "$bin" synth --split test --seed 0 --count 2 --out "$out/test"
  example="$out/test/000001"
fi
[ -f "$out/oracle.vdb" ] || "$bin" oracle "$example" -o "$out/oracle.vdb"
[ -f "$out/example.vdb" ] || "$bin" make-example -o "$out/example.vdb"

echo "## oracle volume of $example (5 x 64^3), against its ground-truth envmaps"
"$bin" bench-sparsity "$out/oracle.vdb" --dataset "$example" --out "$out/oracle"
echo "## bundled example room (5 x 64^3)"
"$bin" bench-sparsity "$out/example.vdb" --out "$out/example"
if [ -n "$extra" ]; then
  echo "## $extra"
  "$bin" bench-sparsity "$extra" --out "$out/extra"
fi
