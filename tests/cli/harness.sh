# Sourced by the CLI test scripts, before they leave the folder they were started in:
#   fresh_workdir DIR   empties DIR (made if missing) and enters it; exits 1 if it cannot
#   fail MESSAGE...     reports one failed check and counts it; the script goes on
#   finish              exits 1 after saying how many checks failed, else says all passed
#   run NAME ARGS...    runs "$lh" ARGS with no input, stdout in NAME.out and stderr in
#                       NAME.err; its status (scripts that need another run define their own)
# (the tests' PASS_REGULAR_EXPRESSION looks for "all cases passed").
failures=0
fail() { echo "FAILED: $*"; failures=$((failures + 1)); }
fresh_workdir() { rm -rf -- "$1" && mkdir -p -- "$1" && cd -- "$1" || exit 1; }
run() {
    local name=$1
    shift
    "$lh" "$@" </dev/null >"$name.out" 2>"$name.err"
}
finish() {
    [ "$failures" -eq 0 ] || { echo "$failures check(s) failed"; exit 1; }
    echo "all cases passed"
}
