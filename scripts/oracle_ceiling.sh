#!/usr/bin/env bash
# The oracle ceiling: how well the lighting-volume layout itself can reproduce ground-truth
# envmaps, for several level counts and resolutions. Generates a synthetic test
# split, voxelises every example's true scene (`lighthouse oracle`), renders the oracle's
# envmaps at the ground-truth points and compares them (`lighthouse compare --batch`).
#
#   bash scripts/oracle_ceiling.sh [COUNT] [OUT]      (defaults: 20 examples, out/oracle_ceiling)
#
# Writes OUT/oracle_ceiling.md (a Markdown table) and prints it.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=build/cli/lighthouse
count=${1:-20}
out=${2:-out/oracle_ceiling}
configs=("5 64" "5 32" "3 64" "5 128")

mkdir -p "$out"
[ -f "$out/test/manifest.json" ] ||
  "$bin" synth --split test --seed 0 --count "$count" -o "$out/test"

table="$out/oracle_ceiling.md"
{
  echo "| layout | PSNR all (dB) | angular all (deg) | PSNR observed (dB) | angular observed (deg) | oracle seconds / example |"
  echo "|---|---|---|---|---|---|"
} > "$table.tmp"
for config in "${configs[@]}"; do
  read -r levels res <<< "$config"
  pred="$out/oracle_${levels}x${res}"
  mkdir -p "$pred"
  start=$(date +%s%N)
  for example in "$out"/test/[0-9]*/; do
    name=$(basename "$example")
    "$bin" oracle "$example" -o "$pred/$name.vdb" --levels "$levels" --res "$res" \
      --envmaps-out "$pred/$name" 2> /dev/null
  done
  ms=$(( ($(date +%s%N) - start) / count / 1000000 ))
  report=$("$bin" compare --batch "$pred" "$out/test")
  all=$(echo "$report" | grep '^all content' | sed 's/all content *//')
  observed=$(echo "$report" | grep '^observed content' | sed 's/observed content *//')
  read -r pa _ pas aa _ aas _ <<< "$all"  # the HDR columns after these are not tabulated here
  read -r po _ pos ao _ aos _ <<< "$observed"
  printf '| %s x %s^3 | %s ± %s | %s ± %s | %s ± %s | %s ± %s | %d.%02d |\n' \
    "$levels" "$res" "$pa" "$pas" "$aa" "$aas" "$po" "$pos" "$ao" "$aos" $((ms / 1000)) $((ms % 1000 / 10)) >> "$table.tmp"
  echo "done: $levels x $res^3" >&2
done
mv "$table.tmp" "$table"
cat "$table"
