#!/usr/bin/env bash
# Reproduces the table "Programs built sparse, and the bound at 1000" of docs/rocking-walls.md:
# `pirqa check --limit --json` on generated running bonds of 495 to 976 blocks and on the
# block-count study's 976-block case 24, with the dense build before (c8be491, its bound raised
# to 2000 for the trial) beside the sparse one (6afed1a), each timed with its peak memory; then
# the uplift check of the block-count study's case 18 with both. Where both builds finish, their
# outputs must be identical to the byte (the script says so). About 30 minutes with the builds.
#
#   bash docs/experiments/limit-sparse.sh [WORKDIR]
set -euo pipefail
source "$(dirname "$0")/scratch-tree.sh"
work=${1:-/tmp/pirqa-limit-sparse}
scratch_tree "$work/dense" c8be491 -c "$raise_limit_bound"
dense=$pirqa
scratch_tree "$work/sparse" 6afed1a
sparse=$pirqa
cd "$work"
"$sparse" generate --blocks 500 -o bond-500.ron
"$sparse" generate --courses 14 --blocks-per-course 56 -o slender-14.ron
"$sparse" generate --blocks 1000 -o bond-1000.ron
for case in 18 24; do
    "$sparse" sweep "$root/walls/studies/block-count.ron" --case "$case" --no-history --out "bc-$case" >/dev/null
done
cp bc-24/case-24/wall.ron case-24.ron
timed() {
    local label=$1
    shift
    /usr/bin/time -f "$label: %e s, %M KB" "$@"
}
# Both builds on one wall, side by side; where both finish, the same JSON to the byte.
for wall in bond-500 slender-14 bond-1000; do
    timed "$wall, dense" "$dense" check "$wall.ron" --limit --json >"$wall-dense.json" &
    timed "$wall, sparse" "$sparse" check "$wall.ron" --limit --json >"$wall-sparse.json" &
    wait
    cmp "$wall-dense.json" "$wall-sparse.json" && echo "$wall: identical"
done
timed "case-24, sparse" "$sparse" check case-24.ron --limit --json >case-24-sparse.json
grep -o '"accel_g": [0-9.]*' case-24-sparse.json
for build in dense sparse; do
    bin=$dense
    [ "$build" = sparse ] && bin=$sparse
    timed "uplift, case 18, $build" "$bin" run bc-18/case-18/wall.ron --record bc-18/case-18/motion.txt \
        --model slide --duration 39.99 --check-uplift --no-history --out "uplift-$build" >/dev/null &
done
wait
cmp uplift-dense/summary.json uplift-sparse/summary.json && echo "uplift, case 18: identical"
echo "remove the scratch trees with: git worktree remove --force $work/dense/tree; git worktree remove --force $work/sparse/tree"
