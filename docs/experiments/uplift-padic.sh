#!/usr/bin/env bash
# Reproduces the times before and after the p-adic solves (docs/rocking-walls.md, "The vertex
# and multipliers by p-adic lifting"): the build before (dbc8efd) and the build with them
# (a5474e2) on the eight 105-block cases with --check-uplift, side by side
# (uplift-two-builds.sh), then both on the limit at rest of the block-count study's 976-block
# case 24 (sampled friction), side by side, their JSON compared. About 25 minutes with the two
# builds.
#
#   bash docs/experiments/uplift-padic.sh [WORKDIR]
set -euo pipefail
work=${1:-/tmp/pirqa-uplift-padic}
bash "$(dirname "$0")/uplift-two-builds.sh" dbc8efd a5474e2 "$work"
source "$(dirname "$0")/scratch-tree.sh"
scratch_builds "$work" dbc8efd a5474e2
cd "$work"
"$after" sweep "$root/walls/studies/block-count.ron" --case 24 --no-history --out bc-24 >/dev/null
for build in before after; do
    bin=$before
    [ "$build" = after ] && bin=$after
    /usr/bin/time -f "case 24 limit at rest, $build: %e s" "$bin" check bc-24/case-24/wall.ron \
        --limit --json >"case-24-$build.json" &
done
wait
cmp case-24-before.json case-24-after.json && echo "case 24: identical"
grep -o '"accel_g": [0-9.]*' case-24-after.json
