#!/usr/bin/env bash
# The uplift check's times of two builds side by side (docs/rocking-walls.md): the
# block-count study's eight 105-block cases (16 to 23, El Centro at 400 gal, sampled friction)
# run with --check-uplift by the build at BEFORE and the build at AFTER, the two at once on the
# two cores, each case's summary.json and events.jsonl compared byte for byte. About 25 minutes
# with the two builds. The scripts that quote it pass their commits.
#
#   bash docs/experiments/uplift-two-builds.sh BEFORE AFTER WORKDIR
set -euo pipefail
source "$(dirname "$0")/scratch-tree.sh"
first=$1 second=$2 work=$3
scratch_builds "$work" "$first" "$second"
cd "$work"
for case in 16 17 18 19 20 21 22 23; do
    "$after" sweep "$root/walls/studies/block-count.ron" --case "$case" --no-history --out "bc-$case" >/dev/null
    dir="bc-$case/case-$case"
    for build in before after; do
        bin=$before
        [ "$build" = after ] && bin=$after
        /usr/bin/time -f "case $case, $build: %e s" "$bin" run "$dir/wall.ron" --record "$dir/motion.txt" \
            --model slide --duration 39.99 --check-uplift --no-history --out "$dir-$build" >/dev/null &
    done
    wait
    cmp "$dir-before/summary.json" "$dir-after/summary.json" &&
        cmp "$dir-before/events.jsonl" "$dir-after/events.jsonl" && echo "case $case: identical"
done
echo "remove the scratch trees with: git worktree remove --force $work/before/tree; git worktree remove --force $work/after/tree"
