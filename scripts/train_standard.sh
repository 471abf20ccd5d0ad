#!/usr/bin/env bash
# Reproduces the bundled model models/standard.pt (models/README.md records the run):
#   1. 1500 synthetic training scenes with their oracle volumes (about 0.85 s each on 2 cores);
#   2. `train` with direct supervision, resumable: run this script again after an interruption
#      and training continues from the checkpoint (outside the repository, in $WORK).
# Then the committed model: OUT in half precision (--half), copied to models/standard.pt. With today's
# code this is one run; the bundled model was made in two phases (models/README.md).
# WORK (default /work/lighthouse-train) holds the data, the checkpoint and the logs.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=build/cli/lighthouse
work=${WORK:-/work/lighthouse-train}
iterations=${ITERATIONS:-1300}
mkdir -p "$work"

"$bin" synth --split train --count 1500 --size 192x144 --envmap-size 120x60 \
  --oracle-levels 5 --oracle-res 64 -o "$work/data/train_a"
"$bin" --threads 2 train --data "$work/data/train_a" --config standard \
  -o "$work/standard.pt" --half --checkpoint "$work/standard.checkpoint" \
  --iterations "$iterations" --lr 4e-4 --validate-every 250 --validation-scenes 6 \
  --log-every 10 --checkpoint-every 50
cp "$work/standard.pt" models/standard.pt
cp "$work/standard.pt.csv" models/standard_training_log.csv
cp "$work/standard.pt.png" models/standard_training_curves.png
