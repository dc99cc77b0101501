#!/usr/bin/env bash
# Reproduces the instruction counts before and after big fractions' products reduced
# crosswise (docs/rocking-walls.md, "Products of big fractions reduced crosswise"): the
# uplift check of the block-count study's case 18 for its first 2.5 s under valgrind's
# callgrind, the build before (a5474e2) and the build with it (b87df4a) side by side, their
# summary.json and events.jsonl compared. About 15 minutes with the two builds.
#
#   bash docs/experiments/uplift-big-products.sh [WORKDIR]
set -euo pipefail
source "$(dirname "$0")/scratch-tree.sh"
work=${1:-/tmp/pirqa-uplift-big-products}
scratch_builds "$work" a5474e2 b87df4a
cd "$work"
"$after" sweep "$root/walls/studies/block-count.ron" --case 18 --no-history --out bc-18 >/dev/null
dir=bc-18/case-18
for build in before after; do
    bin=$before
    [ "$build" = after ] && bin=$after
    valgrind --tool=callgrind --callgrind-out-file="$build.callgrind" "$bin" run "$dir/wall.ron" \
        --record "$dir/motion.txt" --model slide --duration 2.5 --check-uplift --no-history \
        --out "$dir-$build" >/dev/null 2>"$build.log" &
done
wait
for build in before after; do
    echo "$build: $(grep -o 'Collected : [0-9]*' "$build.log")"
done
cmp "$dir-before/summary.json" "$dir-after/summary.json" &&
    cmp "$dir-before/events.jsonl" "$dir-after/events.jsonl" && echo "case 18: identical"
echo "remove the scratch trees with: git worktree remove --force $work/before/tree; git worktree remove --force $work/after/tree"
