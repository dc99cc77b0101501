#!/usr/bin/env bash
# Reproduces the uplift check's times before and after Lehmer's gcd (docs/rocking-walls.md,
# "The uplift check's exact arithmetic"): the block-count study's eight 105-block cases (16 to
# 23, El Centro at 400 gal, sampled friction) run with --check-uplift by the build before
# (16c23e5) and the build with it (e930860), the two side by side on the two cores, each case's
# summary.json compared byte for byte. About 25 minutes with the two builds.
#
#   bash docs/experiments/uplift-gcd.sh [WORKDIR]
set -euo pipefail
source "$(dirname "$0")/scratch-tree.sh"
work=${1:-/tmp/pirqa-uplift-gcd}
scratch_tree "$work/before" 16c23e5
before=$pirqa
scratch_tree "$work/after" e930860
after=$pirqa
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
    cmp "$dir-before/summary.json" "$dir-after/summary.json" && echo "case $case: identical"
done
echo "remove the scratch trees with: git worktree remove --force $work/before/tree; git worktree remove --force $work/after/tree"
