#!/usr/bin/env bash
# The main job on the embedded default input: builds the example lighting volume (a
# procedural room, vdb/example_volume.cpp), describes it, renders envmaps (EXR + PNG) at
# three points and a perspective view from the reference camera. Output: out/demo/.
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
echo "==> done: envmaps and view in $out/ (envmap_000.exr/.png ... view_ref.png)"
