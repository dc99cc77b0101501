#!/usr/bin/env bash
# Reproduces the first trial of "The basis factorised otherwise" (docs/rocking-walls.md, the
# uplift check): the floating-point simplex of the uplift check built with its basis factorised
# every 16, 24, 32, 40, 48 and 64 pivots (limit::revised::REFACTOR_EVERY set by sed in a
# scratch worktree of 118ff00; pirqa keeps 64), and for each
#   1. the instructions of the block-count study's case 18 (105 blocks, El Centro at 400 gal)
#      checked for its first 2.5 s, under valgrind's callgrind (two at a time), and where
#      those of 64 go;
#   2. for 64 and 32, the eight 105-block cases 16 to 23 checked through their 40 s, the two
#      builds side by side on the two cores, timed, and their summary.json and events.jsonl
#      compared (cpu_s aside).
# About 35 minutes: six builds, six callgrind runs of about five minutes, eight timed pairs.
#
#   bash docs/experiments/refactor-every.sh [WORKDIR]
set -euo pipefail
source "$(dirname "$0")/scratch-tree.sh"
work=${1:-/tmp/pirqa-refactor-every}
scratch_tree "$work" 118ff00
every=(16 24 32 40 48 64)
for k in "${every[@]}"; do
    (cd "$tree" &&
        sed -i "s/^const REFACTOR_EVERY: usize = [0-9]*;\$/const REFACTOR_EVERY: usize = $k;/" \
            src/limit/revised.rs &&
        grep -q "^const REFACTOR_EVERY: usize = $k;\$" src/limit/revised.rs &&
        cargo build --release -q)
    cp "$pirqa" "$work/pirqa-$k"
done
(cd "$tree" && git checkout -q src/limit/revised.rs)
for c in 16 17 18 19 20 21 22 23; do
    "$work/pirqa-64" sweep walls/studies/block-count.ron --case $c --no-history --out "$work/bc" \
        >/dev/null
done
checked() { # binary, case, duration, output directory; its run's seconds into DIR.time
    local dir="$work/bc/case-$2"
    /usr/bin/time -f "%e" -o "$4.time" "$1" run "$dir/wall.ron" --record "$dir/motion.txt" \
        --model slide --duration "$3" --check-uplift --no-history --out "$4" >/dev/null 2>&1
}
echo "case 18, first 2.5 s, instructions:"
for pair in "16 24" "32 40" "48 64"; do
    for k in $pair; do
        valgrind --tool=callgrind --callgrind-out-file="$work/cg-$k.out" \
            "$work/pirqa-$k" run "$work/bc/case-18/wall.ron" --record "$work/bc/case-18/motion.txt" \
            --model slide --duration 2.5 --check-uplift --no-history --out "$work/cg-$k" \
            >/dev/null 2>"$work/cg-$k.err" &
    done
    wait
    for k in $pair; do
        echo "  every $k: $(grep -o 'Collected : [0-9]*' "$work/cg-$k.err")"
    done
done
echo "where every 64's go (inclusive: floating-point runs, exact checks, their two solves, the"
echo "factorisations; then the solves' own instructions, nearly all in their eta passes):"
callgrind_annotate --inclusive=yes "$work/cg-64.out" 2>/dev/null | grep -E \
    'revised.rs:pirqa::limit::certify::watched$|certify::basis \[|Factors::solve(_transposed)? \[|Run::refactor \[' |
    sed 's/ \[.*//; s/  */ /g'
callgrind_annotate --inclusive=no "$work/cg-64.out" 2>/dev/null |
    awk '/Run::(btran|ftran)( |$)/ { gsub(",", "", $1); s += $1 }
         /PROGRAM TOTALS/ { gsub(",", "", $1); t = $1 }
         END { printf " %.1f %% btran and ftran themselves\n", 100 * s / t }'
echo "cases 16-23 through 40 s, side by side (every 64, every 32):"
for c in 16 17 18 19 20 21 22 23; do
    for k in 64 32; do
        checked "$work/pirqa-$k" $c 39.99 "$work/run-$k-$c" &
    done
    wait
    same=identical
    diff <(grep -v cpu_s "$work/run-64-$c/summary.json") \
        <(grep -v cpu_s "$work/run-32-$c/summary.json") >/dev/null || same=DIFFERENT
    cmp -s "$work/run-64-$c/events.jsonl" "$work/run-32-$c/events.jsonl" || same=DIFFERENT
    echo "  case $c: $(cat "$work/run-64-$c.time") s, $(cat "$work/run-32-$c.time") s, outputs $same"
done
echo "remove the scratch tree with: git worktree remove --force $tree"
