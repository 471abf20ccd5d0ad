#!/usr/bin/env bash
# The merge job of the pipeline: `lighthouse merge` on each directory that is not merged yet
# (a re-run skips those that are).
#
#   merge_task.sh LIGHTHOUSE DIR...
set -euo pipefail
[ $# -ge 2 ] || { sed -n '2,5p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
exe=$1
shift
for dir in "$@"; do
    if [ -f "$dir/manifest.json" ] || [ -f "$dir/table.md" ] || [ -f "$dir/predictions.json" ]; then
        echo "merge: $dir is merged already"
        continue
    fi
    "$exe" merge "$dir"
done
