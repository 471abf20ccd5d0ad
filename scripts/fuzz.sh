#!/usr/bin/env bash
# Fuzzes the loaders of untrusted input (fuzz/, docs/reliability.md#fuzzing): builds the
# libFuzzer targets with clang, AddressSanitizer and UBSan into build-fuzz/, then runs each for
# SECONDS (default 300) on its committed corpus plus out/fuzz/<target>/corpus/, where the
# inputs it finds are kept (the committed corpus is never written). A crash, leak, UB report,
# timeout (60 s) or memory above 6 GiB stops that target and leaves its input in
# out/fuzz/<target>/. (6 GiB: reading a PNG or JPEG at the 2^28-pixel bound holds 3.75 GiB,
# image/image_io.h, and AddressSanitizer adds its own; a loader that needs more is a bug.) Prints one line per target: CPU time (the target and the .vdb probes it
# starts), executions, exit status.
#
#   bash scripts/fuzz.sh [SECONDS] [TARGET...]      # targets: fuzz/*.cpp, default all
#   taskset -c 1 bash scripts/fuzz.sh 600           # on one chosen core
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-300}
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  targets=(cameras_json vdb_volume image_png image_jpeg image_exr obj_mesh points_file dcc_manifest)
fi
if ! command -v clang++ >/dev/null; then
  echo "lighthouse: error: fuzzing needs clang (apt-get install clang)" >&2
  exit 1
fi
if [ ! -f build-fuzz/CMakeCache.txt ]; then
  cmake -S . -B build-fuzz -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DLIGHTHOUSE_FUZZ=ON -DLIGHTHOUSE_BUILD_TESTS=OFF -DLIGHTHOUSE_BUILD_BENCH=OFF -DLIGHTHOUSE_WITH_TORCH=OFF
fi
cmake --build build-fuzz -- -j2 "${targets[@]/#/fuzz_}"

status=0
for t in "${targets[@]}"; do
  work=out/fuzz/$t
  mkdir -p "$work/corpus"
  dict=()
  [ -f "fuzz/dict/$t.dict" ] && dict=(-dict="fuzz/dict/$t.dict")
  rc=0
  /usr/bin/time -f "%U %S" -o "$work/cpu" nice "build-fuzz/fuzz/fuzz_$t" "${dict[@]}" \
    -max_total_time="$seconds" -rss_limit_mb=6144 -timeout=60 -print_final_stats=1 \
    -artifact_prefix="$work/" "$work/corpus" "fuzz/corpus/$t" >"$work/log" 2>&1 || rc=$?
  # /usr/bin/time appends "Command exited with non-zero status N" before its figures.
  cpu=$(tail -1 "$work/cpu" | awk '{printf "%.1f", ($1 + $2) / 60}')
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$work/log")
  echo "$t: ${cpu} CPU-minutes, ${runs:-?} executions, exit status $rc$([ $rc -ne 0 ] && echo ", see $work/log")"
  [ $rc -eq 0 ] || status=1
done
exit $status
