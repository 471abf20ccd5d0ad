#!/usr/bin/env bash
# From two real photos to an inserted object: cameras -> predict -> insert, on the Middlebury
# "Aloe" stereo pair that Debian's opencv-doc package ships (/usr/share/doc/opencv-doc/
# examples/data/aloeL.jpg, aloeR.jpg; Apache-2.0 AND BSD-3-Clause per the package's copyright
# file; the pair is from D. Scharstein and C. Pal, "Learning conditional random fields for
# stereo", CVPR 2007). The pair is rectified, so `cameras --exif` gives its cameras; the photos
# carry no focal length, so it is given: 3740 px and a 160 mm baseline, the Middlebury 2006
# set's full-size figures. Output: out/real_pair/ (or $OUT).
#   bash scripts/real_pair.sh [DATA_DIR]   (needs: apt-get install opencv-doc)
# LIGHTHOUSE names the binary (default build/cli/lighthouse).
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${LIGHTHOUSE:-build/cli/lighthouse}
data=${1:-/usr/share/doc/opencv-doc/examples/data}
out=${OUT:-out/real_pair}
for f in aloeL.jpg aloeR.jpg; do
  [ -f "$data/$f" ] || { echo "real_pair.sh: $data/$f not found; install it with 'apt-get install opencv-doc' or give its folder" >&2; exit 1; }
done
mkdir -p "$out"

"$bin" cameras --exif "$data/aloeL.jpg" "$data/aloeR.jpg" --fx 3740 --baseline 0.16 -o "$out/cameras.json"
# The plant stands about 2 m from the camera (the depth range is estimated from the pair).
ball=-0.12,0.08,1.9
"$bin" predict --ref "$data/aloeL.jpg" --src "$data/aloeR.jpg" --cameras "$out/cameras.json" \
  --at "$ball" --png -o "$out/aloe.vdb"
"$bin" insert "$out/aloe.vdb" --image "$data/aloeL.jpg" --cameras "$out/cameras.json" \
  --object sphere --at "$ball" --scale 0.05 --material mirror \
  --object sphere --at 0.12,0.1,2.0 --scale 0.05 --material diffuse:0.8,0.8,0.8 -o "$out/inserted.png"
echo "==> done, in $out/: cameras.json, aloe.vdb, aloe_000.png (the envmap at the mirror ball), inserted.png"
