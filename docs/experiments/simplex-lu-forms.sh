#!/usr/bin/env bash
# Reproduces the LU forms of the uplift check's floating-point simplex (docs/rocking-walls.md,
# "The basis factorised otherwise"): the build before (118ff00, faer's high-level sparse LU,
# which picks its simplicial form here and allocates working memory at every solve) against a
# trial (simplex-lu-forms.patch: faer's low-level LU with its storage and working memory kept,
# in the form faer picks, or supernodal where PIRQA_SUPERNODAL is set). For each: the
# instructions of the block-count study's case 18 (105 blocks, El Centro at 400 gal) checked
# for its first 2.5 s under valgrind's callgrind, and whether its whole 40 s run gives the same
# summary.json (cpu_s aside) and events.jsonl as the build before. About 25 minutes.
#
#   bash docs/experiments/simplex-lu-forms.sh [WORKDIR]
set -euo pipefail
source "$(dirname "$0")/scratch-tree.sh"
work=${1:-/tmp/pirqa-simplex-lu-forms}
scratch_tree "$work/base" 118ff00
base=$pirqa
scratch_tree "$work/trial" 118ff00 docs/experiments/simplex-lu-forms.patch
trial=$pirqa
"$base" sweep walls/studies/block-count.ron --case 18 --no-history --out "$work/bc" >/dev/null
dir="$work/bc/case-18"
# name, environment, binary
variants=("before - $base" "kept - $trial" "supernodal PIRQA_SUPERNODAL=1 $trial")
checked() { # name, environment, binary, duration
    env ${2/#-/} "$3" run "$dir/wall.ron" --record "$dir/motion.txt" --model slide \
        --duration "$4" --check-uplift --no-history --out "$work/run-$1-$4" >/dev/null 2>&1
}
for v in "${variants[@]}"; do
    read -r name environment binary <<<"$v"
    env ${environment/#-/} valgrind --tool=callgrind --callgrind-out-file="$work/cg-$name.out" \
        "$binary" run "$dir/wall.ron" --record "$dir/motion.txt" \
        --model slide --duration 2.5 --check-uplift --no-history --out "$work/cg-$name" \
        >/dev/null 2>"$work/cg-$name.err" &
done
wait
for v in "${variants[@]}"; do
    read -r name environment binary <<<"$v"
    checked "$name" "$environment" "$binary" 39.99
    same=identical
    if [ "$name" != before ]; then
        diff <(grep -v cpu_s "$work/run-before-39.99/summary.json") \
            <(grep -v cpu_s "$work/run-$name-39.99/summary.json") >/dev/null || same=DIFFERENT
        cmp -s "$work/run-before-39.99/events.jsonl" "$work/run-$name-39.99/events.jsonl" ||
            same=DIFFERENT
    fi
    echo "$name: first 2.5 s $(grep -o 'Collected : [0-9]*' "$work/cg-$name.err"), 40 s outputs $same"
done
echo "remove the scratch trees with: git worktree remove --force $work/base/tree; git worktree remove --force $work/trial/tree"
