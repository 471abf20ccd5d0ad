#!/usr/bin/env bash
# Reproduces the bundled model models/standard.pt (models/README.md records the run):
#   1. 1988 synthetic training scenes (generator version 3) with three envmaps and a 5 x 64^3
#      oracle volume each (about 1 s per scene on 2 cores, 4.4 GB);
#   2. `train` with direct supervision, fine-tuning (--init) the previous bundled model (from
#      the git history, commit fb252c4), resumable: run this script again after an
#      interruption and training continues from the checkpoint (outside the repository, in
#      $WORK);
#   3. the moving average of the weights in half precision (--half), written from the final
#      checkpoint;
#   4. 500 more iterations on 1200 new scenes (seeds 2000-3199), from step 3's model;
#   5. step 4's run resumed with the squared sRGB envmap loss (--envmap-mse-weight 4): to
#      iteration 1300, then to 1900, written in half precision;
#   6. 1700 iterations on 1200 newer scenes (seeds 3200-4399), fine-tuned from step 5's model;
#   7. 1500 iterations on another 1200 (seeds 4400-5599) with the squared loss weighted 24,
#      fine-tuned from step 6's model;
#   8. the `wide` configuration widened from step 7 (--init-widen: the same predictions),
#      1000 iterations of batch 2 on 3600 scenes (seeds 4400-7999), then 600 more on those
#      of them without over-exposed envmaps (--max-clipped 0.1);
#   9. 1000 more iterations on those scenes with the HDR view loss (--view-hdr-weight 5; the
#      photos are exposed from the views' unclipped EXRs). Its half-precision moving average
#      is the committed model, copied to models/standard.pt.
# The bundled model was trained while the code gained its last losses and augmentations
# (models/README.md says at which iterations); with today's code this is one run.
# WORK (default /work/lighthouse-train) holds the data, the checkpoint and the logs.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=build/cli/lighthouse
work=${WORK:-/work/lighthouse-train}
iterations=${ITERATIONS:-3500}
mkdir -p "$work"
# Every training set: three envmaps and one 5 x 64^3 oracle volume per scene.
scenes=(--envmaps 3 --size 192x144 --envmap-size 120x60 --oracle-levels 5 --oracle-res 64)
progress=(--validation-scenes 6 --checkpoint-every 100 --log-every 25)

"$bin" synth --split train --seed 0 --count 1988 "${scenes[@]}" -o "$work/data/train_v3"
[ -f "$work/previous_standard.pt" ] ||
  git show fb252c4:models/standard.pt > "$work/previous_standard.pt"
train=(--threads 1 train --data "$work/data/train_v3" --config standard
       --init "$work/previous_standard.pt"
       --checkpoint "$work/v3.checkpoint" --iterations "$iterations" --lr 3e-4 --seed 5
       --validate-every 250 "${progress[@]}")
"$bin" "${train[@]}" -o "$work/v3.pt"
# Resumes at the end: writes the model again, in half precision.
"$bin" "${train[@]}" -o "$work/v3_half.pt" --half

"$bin" synth --split train --seed 2000 --count 1200 "${scenes[@]}" -o "$work/data/train_v3b"
finetune=(--threads 1 train --data "$work/data/train_v3b" --config standard
          --init "$work/v3_half.pt" -o "$work/standard.pt"
          --checkpoint "$work/standard.checkpoint" --lr 1.5e-4 --seed 7 "${progress[@]}")
"$bin" "${finetune[@]}" --iterations 500 --validate-every 250
# Step 5: each resume moves the learning rate's drop to 80% of its new --iterations.
squared=(--envmap-mse-weight 4)
"$bin" "${finetune[@]}" "${squared[@]}" --iterations 1300 --validate-every 400
"$bin" "${finetune[@]}" "${squared[@]}" --iterations 1900 --validate-every 300
"$bin" "${finetune[@]}" "${squared[@]}" --iterations 1900 --validate-every 300 --half

"$bin" synth --split train --seed 3200 --count 1200 "${scenes[@]}" -o "$work/data/train_v3c"
step6=(--threads 1 train --data "$work/data/train_v3c" --config standard
       --init "$work/standard.pt" --checkpoint "$work/step6.checkpoint" --iterations 1700
       --lr 1.5e-4 --seed 9 --validate-every 300 "${progress[@]}" "${squared[@]}")
"$bin" "${step6[@]}" -o "$work/step6.pt"
"$bin" "${step6[@]}" -o "$work/step6_half.pt" --half

"$bin" synth --split train --seed 4400 --count 1200 "${scenes[@]}" -o "$work/data/train_v3d"
step7=(--threads 1 train --data "$work/data/train_v3d" --config standard
       --init "$work/step6_half.pt" --checkpoint "$work/step7.checkpoint" --iterations 1500
       --lr 1.5e-4 --seed 11 --validate-every 300 "${progress[@]}" --envmap-mse-weight 24)
"$bin" "${step7[@]}" -o "$work/step7.pt"
"$bin" "${step7[@]}" -o "$work/step7_half.pt" --half

# Step 8: 2400 more scenes, all 3600 of seeds 4400-7999 in one folder (links), the wide model.
"$bin" synth --split train --seed 5600 --count 1200 "${scenes[@]}" -o "$work/data/train_v3e"
"$bin" synth --split train --seed 6800 --count 1200 "${scenes[@]}" -o "$work/data/train_v3f"
mkdir -p "$work/data/train_v3all"
for part in d e f; do
  for scene in "$work/data/train_v3$part"/[0-9]*; do
    ln -sfn "$scene" "$work/data/train_v3all/$part$(basename "$scene")"
  done
done
wide=(--threads 1 train --data "$work/data/train_v3all" --config wide
      --init "$work/step7_half.pt" --init-widen --checkpoint "$work/wide.checkpoint"
      --iterations 1000 --batch 2 --lr 1.5e-4 --seed 37 --validate-every 250
      "${progress[@]}" --envmap-mse-weight 24)
"$bin" "${wide[@]}" -o "$work/wide.pt"
step8=(--threads 1 train --data "$work/data/train_v3all" --max-clipped 0.1 --config wide
       --init "$work/wide.pt" --checkpoint "$work/step8.checkpoint" --iterations 600
       --lr 1e-4 --seed 53 --validate-every 300 "${progress[@]}" --envmap-mse-weight 24)
"$bin" "${step8[@]}" -o "$work/step8.pt"
step9=(--threads 1 train --data "$work/data/train_v3all" --max-clipped 0.1 --config wide
       --init "$work/step8.pt" --checkpoint "$work/step9.checkpoint" --iterations 1000
       --lr 1e-4 --seed 59 --validate-every 300 "${progress[@]}" --envmap-mse-weight 24
       --view-hdr-weight 5)
"$bin" "${step9[@]}" -o "$work/step9.pt"
"$bin" "${step9[@]}" -o "$work/step9_half.pt" --half
cp "$work/step9_half.pt" models/standard.pt
cp "$work/v3.pt.csv" models/standard_training_log.csv
cp "$work/v3.pt.png" models/standard_training_curves.png
cp "$work/standard.pt.csv" models/standard_finetune_log.csv
cp "$work/standard.pt.png" models/standard_finetune_curves.png
cp "$work/step6.pt.csv" models/standard_step6_log.csv
cp "$work/step6.pt.png" models/standard_step6_curves.png
cp "$work/step7.pt.csv" models/standard_step7_log.csv
cp "$work/step7.pt.png" models/standard_step7_curves.png
cp "$work/step8.pt.csv" models/standard_step8_log.csv
cp "$work/step8.pt.png" models/standard_step8_curves.png
cp "$work/step9.pt.csv" models/standard_step9_log.csv
cp "$work/step9.pt.png" models/standard_step9_curves.png
