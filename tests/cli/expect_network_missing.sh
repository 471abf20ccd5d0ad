#!/usr/bin/env bash
# `lighthouse predict` where no `lighthouse-net` lies beside `lighthouse` (a build without
# libtorch, or a copied binary): exit 1 and one error line that says what is missing.
#   expect_network_missing.sh LIGHTHOUSE_EXE
set -u
dir=$(mktemp -d) || exit 1
trap 'rm -rf -- "$dir"' EXIT
cp -- "$1" "$dir/lighthouse" || exit 1
"$dir/lighthouse" --threads 1 predict --ref a.png --src b.png --cameras c.json -o out.vdb >"$dir/out" 2>"$dir/err"
code=$?
status=0
[ "$code" -eq 1 ] || { echo "exit code $code, expected 1"; status=1; }
[ "$(wc -l <"$dir/err")" -eq 1 ] || { echo "expected one line on stderr:"; status=1; }
grep -q "^lighthouse: error: 'predict' needs the prediction network.*lighthouse-net was not found" "$dir/err" ||
    { echo "stderr does not say that lighthouse-net is missing"; status=1; }
cat "$dir/err"
exit $status
