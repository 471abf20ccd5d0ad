#!/usr/bin/env bash
# Memory against envmap error (issue 7, "storing only what the scene needs"): runs
# `lighthouse bench-sparsity` on
#   * an oracle volume of a synthetic room, against its ground-truth envmaps;
#   * the bundled example room (no ground truth: PSNR against the unpruned volume only);
#   * a predicted volume (dense low-alpha fog), against the ground truth of its stereo pair.
#
#   bash scripts/sparsity_study.sh [OUT] [EXAMPLE_DIR] [PREDICTED.vdb] [PREDICTED_DATASET]
#     OUT                default out/sparsity
#     EXAMPLE_DIR        a synthetic example (cameras.json + env_*.exr); default: made with
#                        `lighthouse synth --split test --seed 0 --count 2` under OUT/test
#     PREDICTED.vdb      default: predicted from data/demo_pair with models/small.pt by
#                        $PREDICT (default build/cli/lighthouse, a build with libtorch), as
#                        scripts/demo.sh does; skipped if that binary cannot predict
#     PREDICTED_DATASET  directory whose cameras.json lists the ground-truth envmaps of the
#                        predicted volume; default data/demo_pair
#
# $LIGHTHOUSE (default build/cli/lighthouse) runs everything else.
# Writes OUT/<oracle|example|predicted>/memory_error.{csv,md,svg} and memory_breakdown.{csv,md}
# and prints the tables.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${LIGHTHOUSE:-build/cli/lighthouse}
predict_bin=${PREDICT:-build/cli/lighthouse}
out=${1:-out/sparsity}
example=${2:-}
predicted=${3:-}
predicted_data=${4:-data/demo_pair}
mkdir -p "$out"
if [ -z "$example" ]; then
  [ -f "$out/test/manifest.json" ] || "$bin" synth --split test --seed 0 --count 2 --out "$out/test"
  example="$out/test/000001"
fi
[ -f "$out/oracle.vdb" ] || "$bin" oracle "$example" -o "$out/oracle.vdb"
[ -f "$out/example.vdb" ] || "$bin" make-example -o "$out/example.vdb"
if [ -z "$predicted" ] && "$predict_bin" predict --help >/dev/null 2>&1; then
  predicted="$out/predicted.vdb"
  pair=data/demo_pair
  # The same command as scripts/demo.sh (without its envmaps: bench-sparsity renders them).
  [ -f "$predicted" ] || "$predict_bin" predict --ref "$pair/ref.png" --src "$pair/src.png" \
    --cameras "$pair/cameras.json" -o "$predicted"
fi

echo "## oracle volume of $example, against its ground-truth envmaps"
"$bin" bench-sparsity "$out/oracle.vdb" --dataset "$example" --out "$out/oracle"
echo "## bundled example room"
"$bin" bench-sparsity "$out/example.vdb" --out "$out/example"
if [ -n "$predicted" ]; then
  echo "## predicted volume $predicted, against the ground truth in $predicted_data"
  "$bin" bench-sparsity "$predicted" --dataset "$predicted_data" --out "$out/predicted"
else
  echo "## no predicted volume: pass one, or set PREDICT to a lighthouse built with libtorch"
fi
