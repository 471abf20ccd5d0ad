#!/usr/bin/env bash
# `lighthouse` where no `lighthouse-vdb-probe` lies beside it (a copied binary): .vdb files are
# still read, in-process, after one warning line for the whole run (vdb/safe_read.h), however
# many files it reads (`import` reads one per level).
#   expect_probe_missing.sh LIGHTHOUSE_EXE
set -u
dir=$(mktemp -d) || exit 1
trap 'rm -rf -- "$dir"' EXIT
cp -- "$1" "$dir/lighthouse" || exit 1
cd "$dir" || exit 1
status=0
./lighthouse make-example --levels 3 --res 16 -o ex.vdb >/dev/null 2>err_make ||
    { echo "make-example failed:"; cat err_make; exit 1; }
./lighthouse export ex.vdb --for houdini -o exp >/dev/null 2>err_export || { echo "export failed"; status=1; }
./lighthouse import exp --from houdini -o back.vdb >out 2>err
code=$?
[ "$code" -eq 0 ] || { echo "import: exit code $code, expected 0"; status=1; }
[ -s back.vdb ] || { echo "import wrote no back.vdb"; status=1; }
for f in err_export err; do
    [ "$(wc -l <"$f")" -eq 1 ] || { echo "$f: expected one line on stderr:"; cat "$f"; status=1; }
    grep -q "^warning: lighthouse-vdb-probe was not found beside $dir/lighthouse: .vdb files are read without a trial read in a separate process" "$f" ||
        { echo "$f does not say that lighthouse-vdb-probe is missing:"; cat "$f"; status=1; }
done
exit $status
