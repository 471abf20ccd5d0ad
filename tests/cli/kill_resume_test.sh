#!/usr/bin/env bash
# Commands that write several files, killed with SIGKILL at chosen moments and run again with
# the same command line (docs/reliability.md#interruption):
#   synth   killed in the middle of an example and just after one completed; the same command
#           resumes, keeps the complete examples and ends with the files of an uninterrupted
#           run, byte for byte;
#   export  killed while its temporary directory is being filled, first with no export there,
#           then while replacing one with --force, then at several fixed delays: the final name
#           holds a whole export (the old or the new) or nothing, and the next export removes
#           what the killed one left;
#   predict killed while writing its volume and while writing its envmaps; the same command
#           writes the files of an uninterrupted run;
#   train   killed after its first checkpoint, while a checkpoint is being written and while
#           the model file is being written; the same command resumes from the last complete
#           checkpoint and ends with the weights of an uninterrupted run; the checkpoint and
#           the model load.
# Every part ends with no temporary (a hidden file or folder) left in its output folder.
#   others  render-envmap with several points and eval, killed at fixed delays: every file
#           under its final name is whole, and the same command writes them all.
#   kill_resume_test.sh LIGHTHOUSE WORKDIR synth|export|predict|train|others
set -u
[ $# -eq 3 ] || { echo "usage: $0 LIGHTHOUSE WORKDIR synth|export|predict|train|others" >&2; exit 2; }
lh=$1
work=$2
part=$3
source "$(dirname "$0")/harness.sh"
fresh_workdir "$work"

# start NAME ARGS...: lighthouse ARGS in the background, output in NAME.log; its pid in $pid.
start() {
    local name=$1
    shift
    "$lh" "$@" </dev/null >"$name.log" 2>&1 &
    pid=$!
}
# wait_and_kill NAME PATTERN: SIGKILL the process $pid as soon as a path matching the shell
# PATTERN exists (polled every 2 ms); "PID" in PATTERN stands for $pid, so that a temporary
# an earlier, killed run left cannot match. Returns 1 if the process ends first.
wait_and_kill() {
    local name=$1 pattern=${2//PID/$pid}
    while kill -0 "$pid" 2>/dev/null; do
        if compgen -G "$pattern" >/dev/null; then
            kill -KILL "$pid"
            wait "$pid" 2>/dev/null
            echo "killed $name when $(compgen -G "$pattern" | head -1) existed"
            return 0
        fi
        sleep 0.002
    done
    wait "$pid"
    return 1
}
# kill_when NAME PATTERN: wait_and_kill, and fail the test if the process ends first.
kill_when() {
    wait_and_kill "$@" && return 0
    fail "$1 ended before '$2' appeared, so it was not killed there: $(tail -3 "$1.log")"
    return 1
}
# kill_when_retrying NAME PATTERN CLEANUP ARGS...: start lighthouse ARGS and kill it when
# PATTERN appears. A file that exists for less than the polling interval can be missed on a
# busy machine, so a run that ends first is undone (the command CLEANUP) and tried again,
# up to 10 times.
kill_when_retrying() {
    local name=$1 pattern=$2 cleanup=$3 attempt
    shift 3
    for attempt in 1 2 3 4 5 6 7 8 9 10; do
        start "$name" "$@"
        wait_and_kill "$name" "$pattern" && return 0
        echo "$name ended before '$pattern' appeared (attempt $attempt); trying again"
        eval "$cleanup"
    done
    fail "$name ended before '$pattern' appeared in 10 attempts: $(tail -3 "$name.log")"
    return 1
}
# kill_after NAME SECONDS: SIGKILL the process $pid after SECONDS, if it still runs.
kill_after() {
    sleep "$2"
    if kill -KILL "$pid" 2>/dev/null; then echo "killed $1 after $2 s"; fi
    wait "$pid" 2>/dev/null
    return 0
}
# run NAME ARGS...: lighthouse ARGS in the foreground, output in NAME.log; must succeed.
run() {
    local name=$1
    shift
    "$lh" "$@" </dev/null >"$name.log" 2>&1 || { fail "$name: exit $?: $(tail -5 "$name.log")"; return 1; }
}
# no_temporaries DIR...: nothing hidden (a temporary file or folder) in DIR or below.
no_temporaries() {
    local left
    left=$(find "$@" -mindepth 1 -name '.*' 2>/dev/null)
    [ -z "$left" ] || fail "temporaries left behind: $left"
}

# same_or_absent WHOLE CUT: every file the uninterrupted run wrote to WHOLE is, in CUT, either
# absent or equal to it, and CUT holds no other file under a final (not hidden) name.
same_or_absent() {
    local f
    for f in $(cd "$2" && find . -type f ! -name '.*'); do
        [ -e "$1/$f" ] || fail "$2/$f is not a file the uninterrupted run writes"
        cmp -s "$1/$f" "$2/$f" || fail "$2/$f differs from the uninterrupted run's (a half-written file?)"
    done
}
# same_files WHOLE CUT: the two folders hold the same files under final names, equal byte for byte
# (same_or_absent compares them, once each).
same_files() {
    local f
    for f in $(cd "$1" && find . -type f ! -name '.*'); do
        [ -e "$2/$f" ] || fail "$2/$f is missing: the uninterrupted run wrote it"
    done
    same_or_absent "$1" "$2"
}

tiny=(--seed 5 --size 48x36 --envmap-size 32x16 --envmaps 1 --supersample 1)

case $part in
synth)
    run whole synth "${tiny[@]}" --count 4 -o whole || exit 1
    # Killed while an example after the first is being written (its folder's temporary name
    # exists for some tens of milliseconds).
    kill_when_retrying cut1 "cut/.00000[123].partial" "rm -rf cut" synth "${tiny[@]}" --count 4 -o cut
    [ -f cut/000000/scene.json ] || fail "the complete example 000000 is not under its name"
    for p in cut/.*.partial; do
        id=${p#cut/.}
        [ -e "cut/${id%.partial}" ] && fail "the example being written appeared under its final name"
    done
    [ -e cut/manifest.json ] && fail "a killed synth wrote its manifest"
    # Killed just after the next example is complete, then at a fixed delay.
    start cut2 synth "${tiny[@]}" --count 4 -o cut
    kill_when cut2 "cut/00000[23]/scene.json"
    start cut3 synth "${tiny[@]}" --count 4 -o cut
    kill_after cut3 0.3
    run resumed synth "${tiny[@]}" --count 4 -o cut || exit 1
    no_temporaries cut
    for f in $(cd whole && find . -type f ! -name manifest.json | sort); do
        cmp -s "whole/$f" "cut/$f" || fail "$f differs from the uninterrupted run's"
    done
    [ "$(cd cut && find . -type f | wc -l)" -eq "$(cd whole && find . -type f | wc -l)" ] ||
        fail "the resumed set has other files than the uninterrupted one: $(diff <(cd whole && find . | sort) <(cd cut && find . | sort))"
    # The manifest lists the same examples and seeds (timings and bake statistics aside).
    keep='"(id|example_seed|scene_seed|count|first_index|split)"'
    diff <(grep -E "$keep" whole/manifest.json) <(grep -E "$keep" cut/manifest.json) >/dev/null ||
        fail "the manifests list other examples: $(diff <(grep -E "$keep" whole/manifest.json) <(grep -E "$keep" cut/manifest.json))"
    [ "$(grep -c '"id"' cut/manifest.json)" -eq 4 ] || fail "the resumed manifest does not list 4 examples"
    echo "ok synth_killed_and_resumed"
    ;;

export)
    run volume make-example --levels 3 --res 128 -o room.vdb || exit 1
    run other make-example --levels 2 --res 64 -o other.vdb || exit 1
    # Killed while the first export is being written: nothing under the final name.
    kill_when_retrying exp1 ".exp.tmpPID_*/level_*.vdb" "rm -rf exp" export room.vdb --for blender -o exp
    [ -e exp ] && fail "a killed export left something under its final name"
    run exp1_again export room.vdb --for blender -o exp || exit 1
    no_temporaries exp; [ -z "$(compgen -G '.exp.*')" ] || fail "left beside exp: $(compgen -G '.exp.*')"
    run import1 import exp --from blender -o back1.vdb
    # Killed while replacing it (--force): the old export stays, whole and unchanged.
    cp -a exp exp_before
    kill_when_retrying exp2 ".exp.tmpPID_*/level_*.vdb" "rm -rf exp && cp -a exp_before exp" \
        export room.vdb --for blender --force -o exp
    diff -r exp_before exp >/dev/null || fail "a killed export --force changed the export it was replacing"
    # Killed at fixed delays: whatever the moment, the final name holds a whole export.
    for delay in 0.05 0.1 0.2 0.3 0.35 0.4 0.45; do
        start "exp_$delay" export room.vdb --for blender --force -o exp
        kill_after "exp_$delay" "$delay"
        if [ -f exp/manifest.json ]; then
            run "import_$delay" import exp --from blender -o "back_$delay.vdb"
        elif [ -e exp ]; then
            fail "killed after $delay s: exp exists without its manifest.json"
        fi
    done
    run exp3 export other.vdb --for blender --force -o exp || exit 1
    [ -z "$(compgen -G '.exp.*')" ] || fail "left beside exp: $(compgen -G '.exp.*')"
    no_temporaries exp
    run import3 import exp --from blender -o back3.vdb && grep -q "2 level" import3.log ||
        fail "the last export is not other.vdb's 2 levels: $(cat import3.log)"
    echo "ok export_killed_and_rerun"
    ;;

train)
    run data synth "${tiny[@]}" --count 3 -o syn || exit 1
    # The small network, one thread (bit-reproducible), a checkpoint every iteration.
    train=(--threads 1 train --data syn --config small --iterations 5 --validate-every 100 --validation-scenes 1
           --checkpoint-every 1 --log-every 1)
    run whole "${train[@]}" -o whole.pt || exit 1
    start cut1 "${train[@]}" -o cut.pt
    kill_when cut1 cut.pt.checkpoint
    # Killed while a checkpoint is being written: the previous one stays, whole.
    cp cut.pt.checkpoint first.checkpoint
    # A run that ends before it is caught is undone: back to the first checkpoint.
    kill_when_retrying cut2 ".cut.pt.tmpPID_*.checkpoint" "cp first.checkpoint cut.pt.checkpoint && rm -f cut.pt" \
        "${train[@]}" -o cut.pt
    [ -f cut.pt.checkpoint ] || fail "killed mid-checkpoint: the previous checkpoint is gone"
    [ -n "$(compgen -G ".cut.pt.tmp${pid}_*.checkpoint")" ] || fail "the killed checkpoint's temporary is not there"
    grep -q "resuming from cut.pt.checkpoint at iteration [1-9]" cut2.log || fail "cut2 did not resume: $(cat cut2.log)"
    # Killed while the model file is being written.
    kill_when_retrying cut3 ".cut.tmpPID_*.pt" "rm -f cut.pt" "${train[@]}" -o cut.pt
    run resumed "${train[@]}" -o cut.pt || exit 1
    grep -q "resuming from cut.pt.checkpoint at iteration [1-9]" resumed.log ||
        fail "the last run did not resume: $(cat resumed.log)"
    grep -q "^5," cut.pt.csv || fail "the log does not reach iteration 5: $(cat cut.pt.csv)"
    no_temporaries .
    # The weights equal the uninterrupted run's (each archive's members, whatever its folder name).
    python3 - whole.pt cut.pt <<'EOF' || fail "the resumed model's weights differ from the uninterrupted run's"
import sys, zipfile
def members(path):
    with zipfile.ZipFile(path) as z:
        return {n.split("/", 1)[1]: z.read(n) for n in z.namelist() if "/data/" in n}
a, b = members(sys.argv[1]), members(sys.argv[2])
sys.exit(0 if a and a == b else 1)
EOF
    # The checkpoint loads (the same command resumes at the end) and so does the model.
    run again "${train[@]}" -o cut.pt && grep -q "resuming from cut.pt.checkpoint at iteration 5" again.log ||
        fail "the final checkpoint did not load: $(cat again.log)"
    run predict predict --model cut.pt --ref syn/000000/ref.png --src syn/000000/src.png \
        --cameras syn/000000/cameras.json -o predicted.vdb && [ -s predicted.vdb ] || fail "the model did not load"
    no_temporaries .
    echo "ok train_killed_and_resumed"
    ;;
predict)
    run data synth "${tiny[@]}" --count 1 -o syn || exit 1
    e=syn/000000
    # Large envmaps, so that each EXR takes long enough to write to be caught.
    predict=(--threads 1 predict --ref $e/ref.png --src $e/src.png --cameras $e/cameras.json
             --at 0,0,1.5 --at 0.2,0.1,2 --envmap-size 960x480 --png -o out/p.vdb)
    mkdir -p out whole_out
    run whole "${predict[@]/out\/p.vdb/whole_out/p.vdb}" || exit 1
    # Killed while the volume is being written, then while the envmaps are: no half file ever
    # has a final name, and the same command writes the files of an uninterrupted run.
    kill_when_retrying cut1 "out/.p.tmpPID_*.vdb" "rm -f out/p.vdb out/p_*" "${predict[@]}"
    [ -e out/p.vdb ] && fail "the volume being written appeared under its final name"
    kill_when_retrying cut2 "out/.p_00[01].tmpPID_*.exr" "rm -f out/p_*" "${predict[@]}"
    [ -s out/p.vdb ] || fail "the volume written before the envmaps is missing"
    run rerun "${predict[@]}" || exit 1
    cmp -s <(tail -c +58 out/p.vdb) <(tail -c +58 whole_out/p.vdb) ||
        fail "the re-run's volume differs from the uninterrupted run's"
    for f in p_000.exr p_001.exr p_000.png p_001.png; do
        cmp -s "out/$f" "whole_out/$f" || fail "out/$f differs from the uninterrupted run's"
    done
    no_temporaries out
    echo "ok predict_killed_and_rerun"
    ;;
others)
    # Commands that write several files and start again from the beginning (render-envmap
    # with several points, eval), killed at fixed delays: whatever the moment, every file
    # under its final name equals the uninterrupted run's, and the same command then writes
    # them all.
    run volume make-example --levels 3 --res 128 -o room.vdb || exit 1
    envmaps=(render-envmap room.vdb --at 0,0,2 --at 0.2,0.1,0.45 --at -1,0.5,4 --size 960x480 --png)
    mkdir -p env_whole env
    run env_whole "${envmaps[@]}" -o env_whole/e.exr || exit 1
    # Killed once the first envmap is complete, while a later one is being written, and at
    # fixed delays.
    start env_a "${envmaps[@]}" -o env/e.exr
    kill_when env_a "env/e_000.png"
    same_or_absent env_whole env
    kill_when_retrying env_b "env/.e_00[12].tmpPID_*.exr" "rm -f env/e_*" "${envmaps[@]}" -o env/e.exr
    same_or_absent env_whole env
    for delay in 0.5 1 1.5; do
        start "env_$delay" "${envmaps[@]}" -o env/e.exr
        kill_after "env_$delay" "$delay"
        same_or_absent env_whole env
    done
    run env_rerun "${envmaps[@]}" -o env/e.exr || exit 1
    same_files env_whole env
    no_temporaries env
    echo "ok render_envmap_killed_and_rerun"
    if "$lh" eval --help >/dev/null 2>&1; then
        run data synth "${tiny[@]}" --split test --count 2 -o syn || exit 1
        evaluate=(--threads 1 eval --data syn --no-oracle)
        run eval_whole "${evaluate[@]}" -o eval_whole || exit 1
        # Killed as soon as one of its files has its final name (when the poll sees it before
        # the command ends), then at fixed delays.
        start eval_a "${evaluate[@]}" -o eval_cut
        wait_and_kill eval_a "eval_cut/[a-z]*" || echo "eval_a ended before it was caught"
        same_or_absent eval_whole eval_cut
        for delay in 0.5 1 1.5 2 2.5 3; do
            start "eval_$delay" "${evaluate[@]}" -o eval_cut
            kill_after "eval_$delay" "$delay"
            [ -d eval_cut ] && same_or_absent eval_whole eval_cut
        done
        run eval_rerun "${evaluate[@]}" -o eval_cut || exit 1
        same_files eval_whole eval_cut
        no_temporaries eval_cut
        echo "ok eval_killed_and_rerun"
    fi
    ;;
*)
    echo "unknown part '$part'" >&2
    exit 2
    ;;
esac
finish
