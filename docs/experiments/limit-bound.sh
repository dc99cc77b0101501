#!/usr/bin/env bash
# Reproduces the table "Raising the bound" of docs/rocking-walls.md: the limit at rest of
# generated running bonds up to and beyond limit::MAX_BLOCKS (600), in a scratch worktree whose
# bound is raised to 2000 (pirqa itself refuses the largest). Each `pirqa check --limit` is timed
# and stopped after 400 s. About 10 minutes with the build.
#
#   bash docs/experiments/limit-bound.sh [WORKDIR]
set -euo pipefail
source "$(dirname "$0")/scratch-tree.sh"
work=${1:-/tmp/pirqa-limit-bound}
scratch_tree "$work" bd68838 -c "$raise_limit_bound"
walls=()
for n in 203 250 297 320 360 400 450 500 550 600 700; do
    "$pirqa" generate --blocks "$n" -o "$work/bond-$n.ron"
    walls+=("$work/bond-$n.ron")
done
for courses in 8 10 12; do
    "$pirqa" generate --courses "$courses" --blocks-per-course $((4 * courses)) -o "$work/slender-$courses.ron"
    walls+=("$work/slender-$courses.ron")
done
for w in "${walls[@]}"; do
    /usr/bin/time -f "$(basename "$w"): %e s, %M KB" timeout -s KILL 400 \
        "$pirqa" check "$w" --limit 2>&1 | grep -E 'wrote|held up|s, [0-9]+ KB' || true
done
echo "remove the scratch tree with: git worktree remove --force $tree"
