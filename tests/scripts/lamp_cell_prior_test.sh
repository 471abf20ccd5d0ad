#!/usr/bin/env bash
# scripts/lamp_cell_prior.py on four scenes with known lamp cells (far 4 m: level 0 is 8 m wide,
# cells of 1 m): three with their lamp in one cell, one in another. Leave one out, the three
# see 2/3 of the others there and the fourth none, so the mean divergence is
# (3 (-ln(0.999 x 2/3 + 0.001/512)) + ln(512000)) / 4 = 3.591 nats; uniform, ln 512 = 6.238.
# A folder without files and a scene without lamps are left out; too few scenes is refused.
set -euo pipefail
script="$(dirname "$0")/../../scripts/lamp_cell_prior.py"
fail() { echo "FAIL: $*" >&2; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

scene() {  # folder, then the emission and centre of one primitive
  mkdir -p "$dir/$1"
  echo '{"far": 4.0, "near": 1.0}' > "$dir/$1/cameras.json"
  echo "{\"primitives\": [{\"emission\": \"none\", \"centre\": [3, 3, 3]},
        {\"emission\": \"$2\", \"centre\": [$3]}]}" > "$dir/$1/scene.json"
}
scene a area "0.5, 0.5, 0.5"
scene b area "0.2, 0.9, 0.1"
scene c window "0.7, 0.1, 0.6"
scene d area "-3.5, 0.5, 0.5"
scene e none "0, 0, 0"  # no lamps: left out
mkdir -p "$dir/f"       # no files: left out

out=$(/usr/bin/python3 "$script" "$dir" 2>&1) || fail "exited non-zero: $out"
echo "$out"
grep -q "^scenes with lamps: 4; cells that hold one: 2 of 512$" <<< "$out" || fail "scene count"
grep -q "leave one out): 3.591 nats$" <<< "$out" || fail "marginal divergence"
grep -q "uniform): 6.238 nats$" <<< "$out" || fail "uniform divergence"
grep -q "skipping .*/f" <<< "$out" || fail "the empty folder is not reported"

rm -rf "$dir/b" "$dir/c" "$dir/d"
if /usr/bin/python3 "$script" "$dir" > "$dir/one.txt" 2>&1; then fail "one scene accepted"; fi
grep -q "has 1 scenes with lamps; at least 2 needed" "$dir/one.txt" || fail "$(cat "$dir/one.txt")"
echo "lamp_cell_prior_test: ok"
