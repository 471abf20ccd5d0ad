#!/usr/bin/env bash
# The performance study's figures in one command: speed against error and memory against error on three
# volumes, and the targets read from those runs.
#
#   bash scripts/performance_study.sh [--quick] [--docs] [OUT]      (OUT default out/performance)
#
# Volumes (made under OUT unless already there):
#   oracle     the true light of synthetic test example 000001 (`synth --split test --seed 0
#              --count 2`, then `oracle`), 5 x 64^3, with ground-truth envmaps;
#   example    the bundled procedural example room (`make-example`), 5 x 64^3;
#   predicted  the bundled model's fog for data/demo_pair (5 x 64^3, `predict --no-shell`),
#              with the pair's ground-truth envmaps; skipped, with a note, in a build without
#              lighthouse-net.
# Per volume: `bench-envmap` (OUT/<volume>/speed/speed_error.{csv,md,svg}) and `bench-sparsity`
# (OUT/<volume>/memory/memory_error.{csv,md,svg}, memory_breakdown.{csv,md}). Then
# OUT/summary.md: the machine, the commit, each run's targets and the plots; it is printed too.
#
#   --quick   small envmaps (60x30), 2 points, 1 timing round, two sparsity bounds: checks that
#             everything runs (15 s); its times do not measure the targets.
#   --docs    also copy the reports (summary.md, every table, CSV and plot) to docs/study/,
#             which the README and docs/performance.md show.
#
# The full run takes about 7 minutes on this 2-core machine. Time only on an otherwise idle
# machine: every timing is compared within its own run, but a busy machine slows some
# methods more than others. $LIGHTHOUSE (default build/cli/lighthouse) runs every command.
set -euo pipefail
cd "$(dirname "$0")/.."

quick=0 docs=0 out=
for arg in "$@"; do
  case "$arg" in
    --quick) quick=1 ;;
    --docs) docs=1 ;;
    -h|--help) sed -n '2,24p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) echo "performance_study.sh: error: unknown option '$arg' (see --help)" >&2; exit 2 ;;
    *) [ -z "$out" ] || { echo "performance_study.sh: error: one output directory only" >&2; exit 2; }
       out=$arg ;;
  esac
done
[ "$quick" = 0 ] || [ "$docs" = 0 ] ||
  { echo "performance_study.sh: error: --docs keeps full runs only (drop --quick)" >&2; exit 2; }
out=${out:-out/performance}
bin=${LIGHTHOUSE:-build/cli/lighthouse}
[ -x "$bin" ] || { echo "performance_study.sh: error: $bin not found: build first (bash scripts/build.sh)" >&2; exit 1; }

if [ "$quick" = 1 ]; then
  speed_args=(--count 2 --repeats 1 --size 60x30)
  memory_args=(--count 1 --size 60x30 --taus 1e-4,1e-1)
else
  speed_args=(--count 8 --repeats 10)
  memory_args=()
fi
# The pruned volumes are rendered as their half-precision files read back.
memory_args+=(--half)
step=0
say() { step=$((step + 1)); echo "==> [$step] $*" >&2; }

mkdir -p "$out"
say "volumes in $out/"
if [ ! -f "$out/oracle.vdb" ]; then
  [ -f "$out/test/manifest.json" ] || "$bin" synth --split test --seed 0 --count 2 -o "$out/test" >&2
  "$bin" oracle "$out/test/000001" -o "$out/oracle.vdb" >&2
fi
[ -f "$out/example.vdb" ] || "$bin" make-example -o "$out/example.vdb" >&2
volumes=(oracle example)
datasets=("$out/test/000001" "")
if "$bin" predict --help >/dev/null 2>&1; then
  # The network's own medium, the hard case (docs/performance.md), not predict's default shell.
  pair=data/demo_pair
  [ -f "$out/predicted.vdb" ] || "$bin" predict --ref "$pair/ref.png" --src "$pair/src.png" \
    --cameras "$pair/cameras.json" --no-shell -o "$out/predicted.vdb" >&2
  volumes+=(predicted)
  datasets+=("$pair")
else
  echo "note: this build has no prediction network (lighthouse-net): no predicted volume" >&2
fi

for i in "${!volumes[@]}"; do
  v=${volumes[$i]}
  # The oracle gets every method; the others the reference check, ours and the paper's.
  methods=()
  [ "$v" = oracle ] || methods=(--methods reference-check ours-cells paper-spheres)
  say "speed against error: $v"
  "$bin" bench-envmap "$out/$v.vdb" "${speed_args[@]}" "${methods[@]}" -o "$out/$v/speed" > /dev/null
  say "memory against error: $v"
  dataset=()
  [ -z "${datasets[$i]}" ] || dataset=(--dataset "${datasets[$i]}")
  "$bin" bench-sparsity "$out/$v.vdb" "${memory_args[@]}" "${dataset[@]}" -o "$out/$v/memory" > /dev/null
done

# The summary: every run's own reading of the targets, then where the tables and plots are.
say "summary: $out/summary.md"
section() {  # the lines of file $1 from the heading that starts with $2 to the end
  sed -n "/^## $2/,\$p" "$1"
}
{
  echo "# Speed, error and memory (scripts/performance_study.sh)"
  echo
  echo "* command: \`bash scripts/performance_study.sh$([ "$quick" = 1 ] && echo " --quick")\`"
  echo "* commit $(git rev-parse --short HEAD 2>/dev/null || echo unknown)$(git diff --quiet HEAD 2>/dev/null || echo ', with uncommitted changes')"
  echo "* machine: $(nproc) cores, $(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1)"
  [ "$quick" = 0 ] || echo "* **quick run** (60x30 envmaps, 2 points, 1 round): its times do not measure the targets"
  for v in "${volumes[@]}"; do
    echo
    echo "# $v ($("$bin" info "$out/$v.vdb" | head -n 1 | sed 's/^[^:]*: //'))"
    echo
    section "$out/$v/speed/speed_error.md" "Against the targets" | sed 's/^## /### Speed: /'
    echo
    echo "![speed against error, $v]($v/speed/speed_error.svg)"
    echo
    section "$out/$v/memory/memory_error.md" "Against the target" | sed 's/^## /### Memory: /'
    echo
    echo "![memory against error, $v]($v/memory/memory_error.svg)"
    echo
    echo "Every row: [$v/speed/speed_error.md]($v/speed/speed_error.md), [$v/memory/memory_error.md]($v/memory/memory_error.md), [$v/memory/memory_breakdown.md]($v/memory/memory_breakdown.md)."
  done
} > "$out/summary.md.tmp"
mv "$out/summary.md.tmp" "$out/summary.md"

if [ "$docs" = 1 ]; then
  say "reports -> docs/study/"
  rm -rf docs/study.tmp
  for v in "${volumes[@]}"; do
    for part in speed memory; do
      mkdir -p "docs/study.tmp/$v/$part"
      cp "$out/$v/$part"/*.md "$out/$v/$part"/*.csv "$out/$v/$part"/*.svg "docs/study.tmp/$v/$part/"
    done
  done
  cp "$out/summary.md" docs/study.tmp/
  rm -rf docs/study && mv docs/study.tmp docs/study
fi
cat "$out/summary.md"
