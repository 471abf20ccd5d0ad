#!/usr/bin/env bash
# Runs a command that must succeed, and checks what it printed and wrote.
#
#   expect_success.sh [OPTIONS] -- COMMAND [ARGS...]
#
#   -o, --stdout REGEX   stdout must match this extended regular expression; repeatable
#   -f, --file PATH      PATH must exist and be non-empty afterwards; deleted before the run
#       --png PATH       as --file, and PATH must start with the PNG signature
#       --exr PATH       as --file, and PATH must start with the OpenEXR magic number
#   -n, --no-file PATH   PATH must not exist afterwards; deleted before the run
#
# The exit code must be 0 and stderr must not mention "error" (case-insensitive). The
# command runs with stdin from /dev/null. On failure the script prints why, with the
# command's stdout and stderr, and exits 1.
set -u

usage() {
    sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//' >&2
    exit 2
}

stdout_res=()
files=()   # "kind:path", kind = any | png | exr
missing=()
while [ $# -gt 0 ]; do
    case $1 in
        -o | --stdout) [ $# -ge 2 ] || usage; stdout_res+=("$2"); shift 2 ;;
        -f | --file) [ $# -ge 2 ] || usage; files+=("any:$2"); shift 2 ;;
        --png) [ $# -ge 2 ] || usage; files+=("png:$2"); shift 2 ;;
        --exr) [ $# -ge 2 ] || usage; files+=("exr:$2"); shift 2 ;;
        -n | --no-file) [ $# -ge 2 ] || usage; missing+=("$2"); shift 2 ;;
        --) shift; break ;;
        *) echo "expect_success.sh: unknown option '$1'" >&2; usage ;;
    esac
done
[ $# -ge 1 ] || usage

for f in "${files[@]+"${files[@]}"}"; do rm -f -- "${f#*:}"; done
for f in "${missing[@]+"${missing[@]}"}"; do rm -f -- "$f"; done

out=$(mktemp) && err=$(mktemp) || { echo "expect_success.sh: mktemp failed" >&2; exit 1; }
trap 'rm -f -- "$out" "$err"' EXIT

"$@" </dev/null >"$out" 2>"$err"
code=$?

# First bytes of a file as lowercase hex.
magic() { head -c "$2" -- "$1" | od -An -tx1 | tr -d ' \n'; }

problems=()
[ $code -eq 0 ] || problems+=("exit code $code, expected 0")
if grep -qi 'error' "$err"; then problems+=("stderr mentions an error"); fi
for re in "${stdout_res[@]+"${stdout_res[@]}"}"; do
    grep -Eq -- "$re" "$out" || problems+=("stdout does not match /$re/")
done
for f in "${files[@]+"${files[@]}"}"; do
    kind=${f%%:*}
    path=${f#*:}
    if [ ! -s "$path" ]; then
        problems+=("expected output '$path' is missing or empty")
        continue
    fi
    case $kind in
        png) [ "$(magic "$path" 8)" = 89504e470d0a1a0a ] || problems+=("'$path' is not a PNG") ;;
        exr) [ "$(magic "$path" 4)" = 762f3101 ] || problems+=("'$path' is not an OpenEXR file") ;;
    esac
done
for f in "${missing[@]+"${missing[@]}"}"; do
    [ -e "$f" ] && problems+=("'$f' should not have been written")
done

if [ ${#problems[@]} -eq 0 ]; then
    echo "ok: $*"
    exit 0
fi
echo "FAILED: $*"
for m in "${problems[@]}"; do echo "  - $m"; done
echo "---- exit code: $code"
echo "---- stdout:"
cat "$out"
echo "---- stderr:"
cat "$err"
exit 1
