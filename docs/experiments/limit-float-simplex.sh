#!/usr/bin/env bash
# Reproduces the trials of docs/rocking-walls.md ("The limit at rest", Cost) that decided to keep
# limit::MAX_BLOCKS at 150 and Bland's rule in the floating-point simplex:
#   1. the limit at rest of generated running bonds beyond 150 blocks, with the float run as
#      shipped (203 blocks: about 2 s; 300 blocks: not finished in 200 s);
#   2. the uplift check of the block-count study's case 16 (105 blocks, sampled friction) with
#      Dantzig's rule, Harris's ratio test, perturbed bounds and the tableau refactorised every
#      50 pivots: every program's pivots and time, and whether its basis is certified.
#
# The trial code is temporary, not part of pirqa: limit-float-simplex.patch, applied in a git
# worktree at the commit it was written against, raises MAX_BLOCKS to 500, prints each float
# run's time and certificate, and takes the experimental simplex where PIRQA_SIMPLEX=dantzig.
# About 10 minutes.
#
#   bash docs/experiments/limit-float-simplex.sh [WORKDIR]
set -euo pipefail
source "$(dirname "$0")/scratch-tree.sh"
work=${1:-/tmp/pirqa-limit-simplex}
scratch_tree "$work" 979b6fd400fb4437d16329f3d0da8b75fb167820 docs/experiments/limit-float-simplex.patch

for blocks in 200 300; do
    "$pirqa" generate --blocks "$blocks" -o "$work/bond-$blocks.ron"
    /usr/bin/time -f "limit at rest of bond-$blocks: %e s" timeout -s KILL 200 \
        "$pirqa" check "$work/bond-$blocks.ron" --limit 2>&1 | grep -E 'held up to|limit at rest of|EXPERIMENT' || true
done

"$pirqa" sweep walls/studies/block-count.ron --case 16 --out "$work/cases" --no-history >/dev/null
dir="$work/cases/case-16"
PIRQA_SIMPLEX=dantzig timeout -s KILL 120 "$pirqa" run "$dir/wall.ron" --record "$dir/motion.txt" \
    --model slide --duration 39.99 --out "$work/run-16" --no-history --check-uplift 2>&1 \
    | grep EXPERIMENT || true
