#!/usr/bin/env bash
# Runs a command that must fail cleanly, and checks how it failed.
#
#   expect_error.sh [OPTIONS] -- COMMAND [ARGS...]
#
#   -e, --expect REGEX   stderr must match this extended regular expression (grep -E);
#                        required, repeatable (every one must match)
#   -a, --absent PATH    PATH must not exist after the command, nor any dot-temporary beside
#                        it (.STEM.tmp*, the AtomicOutput naming, or .NAME*); repeatable.
#                        PATH is deleted before the run so that stale files do not count.
#   -p, --parse-error    the failure is a command-line parse error (unknown option, missing
#                        or bad value): besides the default checks, the exit code must be
#                        exactly 1 and stderr exactly one line (CLI11's own report is two
#                        lines with exit codes 100-127)
#   -m, --max-memory MB  run under `ulimit -v` (virtual memory, MiB), default 4096, so that
#                        a command that ignores a memory bound fails here instead of
#                        exhausting the machine
#
# Default checks (an error reported by lighthouse itself):
#   - the exit code is exactly 1 or 2 (not 0, not a crash or signal: those give >= 128)
#   - stderr matches every --expect regex
#   - exactly one stderr line mentions "error" (case-insensitive), and it starts with
#     "lighthouse: error: "
#   - every --absent path (and its temporaries) is missing afterwards
# The command runs with stdin from /dev/null. On failure the script prints why, with the
# command's stdout and stderr, and exits 1; on success it exits 0.
set -u

usage() {
    sed -n '2,25p' "$0" | sed 's/^# \{0,1\}//' >&2
    exit 2
}

patterns=()
absent=()
parse_error=0
max_mb=4096
while [ $# -gt 0 ]; do
    case $1 in
        -e | --expect) [ $# -ge 2 ] || usage; patterns+=("$2"); shift 2 ;;
        -a | --absent) [ $# -ge 2 ] || usage; absent+=("$2"); shift 2 ;;
        -p | --parse-error) parse_error=1; shift ;;
        -m | --max-memory) [ $# -ge 2 ] || usage; max_mb=$2; shift 2 ;;
        --) shift; break ;;
        *) echo "expect_error.sh: unknown option '$1'" >&2; usage ;;
    esac
done
[ $# -ge 1 ] || usage
[ ${#patterns[@]} -ge 1 ] || { echo "expect_error.sh: give at least one --expect REGEX" >&2; usage; }

# Temporaries an atomic writer may leave beside PATH: .STEM.tmp* and .NAME*.
temporaries_of() {
    local path=$1 dir name stem f
    dir=$(dirname -- "$path")
    name=$(basename -- "$path")
    stem=${name%.*}
    [ -d "$dir" ] || return 0
    for f in "$dir"/."$stem".tmp* "$dir"/."$name"*; do
        [ -e "$f" ] && echo "$f"
    done
    return 0
}

for p in "${absent[@]+"${absent[@]}"}"; do
    rm -f -- "$p"
    temporaries_of "$p" | while IFS= read -r t; do rm -f -- "$t"; done
done

out=$(mktemp) && err=$(mktemp) || { echo "expect_error.sh: mktemp failed" >&2; exit 1; }
trap 'rm -f -- "$out" "$err"' EXIT

( ulimit -v $((max_mb * 1024)) 2>/dev/null; exec "$@" ) </dev/null >"$out" 2>"$err"
code=$?

problems=()
if [ $parse_error -eq 1 ]; then
    [ $code -eq 1 ] || problems+=("exit code $code, expected 1 for a parse error")
    lines=$(wc -l <"$err")
    [ "$lines" -eq 1 ] || problems+=("stderr has $lines lines, expected one for a parse error")
fi
if [ $code -ne 1 ] && [ $code -ne 2 ]; then
    if [ $code -eq 0 ]; then
        problems+=("exit code 0: the command succeeded but should have failed")
    elif [ $code -ge 128 ]; then
        problems+=("exit code $code: killed by signal $((code - 128)) (crash?)")
    else
        problems+=("exit code $code, expected 1 or 2")
    fi
fi
n=$(grep -ci 'error' "$err")
if [ "$n" -ne 1 ]; then
    problems+=("stderr has $n lines mentioning 'error', expected exactly one")
fi
if ! grep -qi 'error' "$err" || ! grep -i 'error' "$err" | grep -q '^lighthouse: error: '; then
    problems+=("the error line does not start with 'lighthouse: error: '")
fi
for re in "${patterns[@]}"; do
    grep -Eq -- "$re" "$err" || problems+=("stderr does not match /$re/")
done
for p in "${absent[@]+"${absent[@]}"}"; do
    [ -e "$p" ] && problems+=("output '$p' exists after the failed command")
    while IFS= read -r t; do
        [ -n "$t" ] && problems+=("temporary '$t' left behind")
    done < <(temporaries_of "$p")
done

if [ ${#problems[@]} -eq 0 ]; then
    echo "ok (exit $code): $(head -n 1 "$err")"
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
