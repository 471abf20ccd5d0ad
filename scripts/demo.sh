#!/usr/bin/env bash
# The main job on the embedded default input: builds the example lighting volume (a
# procedural room, vdb/example_volume.cpp), describes it, renders envmaps (EXR + PNG) at
# three points and a perspective view from the reference camera, then inserts three objects
# into a synthetic photograph lit by a lighting volume. Output: out/demo/.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=build/cli/lighthouse
out=out/demo
mkdir -p "$out"

"$bin" make-example -o "$out/example.vdb" --cameras "$out/cameras.json"
"$bin" info "$out/example.vdb"
# Points in the room (metres, reference camera frame: +x right, +y down, +z forward).
"$bin" render-envmap "$out/example.vdb" --at 0,0,2 --at 0.2,0.1,0.45 --at -1,0.5,4 \
  --size 240x120 --png -o "$out/envmap.exr"
"$bin" render-view "$out/example.vdb" --cameras "$out/cameras.json" --view ref -o "$out/view_ref.png"

# Object insertion into a photograph. Until the prediction network lands (issue 4), the photo
# is a synthetic example (deterministic by seed) and its light comes from the example's
# oracle volume; the prediction issue replaces the oracle with the predicted volume.
"$bin" synth --split test --seed 0 --count 2 --out "$out/scene"
photo="$out/scene/000001"
"$bin" oracle "$photo" -o "$out/scene_oracle.vdb"
objects=(--object sphere --at 0.3,0.32,1.12 --scale 0.15 --rotate 0,0,0 --material mirror
         --object torus --at -0.83,-0.39,3.13 --scale 0.3 --rotate 60,20,0 --material glossy:0.25
         --object cube --at -0.25,0.35,1.5 --scale 0.12 --rotate 20,40,0 --material diffuse:0.8,0.3,0.2)
"$bin" insert --volume "$out/scene_oracle.vdb" --image "$photo/ref.exr" --cameras "$photo/cameras.json" \
  "${objects[@]}" --png -o "$out/inserted.exr"
"$bin" insert --volume "$out/scene_oracle.vdb" --image "$photo/ref.exr" --cameras "$photo/cameras.json" \
  "${objects[@]}" --single-envmap -o "$out/inserted_single_envmap.png"
echo "==> done: envmaps and view of the example volume, and objects inserted into a photo, in $out/"
echo "    envmap_000.png ... view_ref.png, inserted.png (per-point lighting), inserted_single_envmap.png"
