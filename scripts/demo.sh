#!/usr/bin/env bash
# The main job on the embedded default input, the full pipeline:
#  1. predict a lighting volume from the bundled stereo pair (data/demo_pair: a synthetic test
#     scene the model never saw) with the bundled model (models/standard.pt);
#  2. render envmaps from it at the two points where the pair's ground truth was taken, and
#     score them (PSNR, RGB angular error) against that ground truth;
#  3. insert three virtual objects into the reference photo, lit by the predicted volume at
#     every surface point (and, for comparison, by one envmap per object);
#  4. also build the procedural example room volume and render envmaps and a view of it.
# Output: out/demo/.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=build/cli/lighthouse
out=out/demo
pair=data/demo_pair
mkdir -p "$out"

if "$bin" predict --help >/dev/null 2>&1; then
  # Ground-truth envmap positions of the pair (reference camera frame, metres).
  at0=0.2957831,0.319871,1.1225537
  at1=-0.8327363,-0.3857153,3.127743
  "$bin" predict --ref "$pair/ref.png" --src "$pair/src.png" --cameras "$pair/cameras.json" \
    --at "$at0" --at "$at1" --png -o "$out/predicted.vdb"
  "$bin" info "$out/predicted.vdb"
  "$bin" compare "$out/predicted_000.exr" "$pair/env_0.exr" --mask "$pair/env_0_mask.png"
  "$bin" compare "$out/predicted_001.exr" "$pair/env_1.exr" --mask "$pair/env_1_mask.png"

  objects=(--object sphere --at 0.3,0.32,1.12 --scale 0.15 --rotate 0,0,0 --material mirror
           --object torus --at -0.83,-0.39,3.13 --scale 0.3 --rotate 60,20,0 --material glossy:0.25
           --object cube --at -0.25,0.35,1.5 --scale 0.12 --rotate 20,40,0 --material diffuse:0.8,0.3,0.2)
  "$bin" insert "$out/predicted.vdb" --image "$pair/ref.png" --cameras "$pair/cameras.json" \
    "${objects[@]}" --png -o "$out/inserted.exr"
  "$bin" insert "$out/predicted.vdb" --image "$pair/ref.png" --cameras "$pair/cameras.json" \
    "${objects[@]}" --single-envmap -o "$out/inserted_single_envmap.png"
else
  echo "==> this build has no prediction network (libtorch missing): skipping predict and insert"
fi

"$bin" make-example -o "$out/example.vdb" --cameras "$out/cameras.json"
"$bin" render-envmap "$out/example.vdb" --at 0,0,2 --at 0.2,0.1,0.45 --at -1,0.5,4 \
  --size 240x120 --png -o "$out/envmap.exr"
"$bin" render-view "$out/example.vdb" --cameras "$out/cameras.json" --view ref -o "$out/view_ref.png"
echo "==> done, in $out/:"
echo "    predicted.vdb, predicted_000.png / predicted_001.png (envmaps of the predicted volume),"
echo "    inserted.png (objects lit by the predicted volume per point), inserted_single_envmap.png,"
echo "    envmap_000.png ... and view_ref.png of the procedural example room"
