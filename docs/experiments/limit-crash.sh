#!/usr/bin/env bash
# Reproduces the trial of the limit at rest from the crash basis (docs/rocking-walls.md, "The
# crash for the interval's programs too"): the build at 96e99c4 (the limit at rest from the
# artificial basis) against the same with limit-crash.patch applied (its programs from the
# crash's groups), on three generated running bonds, `pirqa check --limit --json` timed and
# compared, then every shipped wall's limit compared. About 10 minutes with the two builds.
#
#   bash docs/experiments/limit-crash.sh [WORKDIR]
set -euo pipefail
source "$(dirname "$0")/scratch-tree.sh"
work=${1:-/tmp/pirqa-limit-crash}
scratch_tree "$work/before" 96e99c4
before=$pirqa
scratch_tree "$work/after" 96e99c4 docs/experiments/limit-crash.patch
after=$pirqa
cd "$work"
"$after" generate --blocks 250 -o bond-250.ron
"$after" generate --courses 10 --blocks-per-course 40 -o slender-10.ron
"$after" generate --blocks 500 -o bond-500.ron
for wall in bond-250 slender-10 bond-500; do
    for build in before after; do
        bin=$before
        [ "$build" = after ] && bin=$after
        /usr/bin/time -f "$wall, $build: %e s" "$bin" check "$wall.ron" --limit --json >"$wall-$build.json"
    done
    cmp -s "$wall-before.json" "$wall-after.json" && echo "$wall: identical" || echo "$wall: differs"
done
for wall in "$root"/walls/*.ron "$root"/walls/inca/*.ron "$root"/walls/rocking/*.ron; do
    name=$(basename "$wall" .ron)
    "$before" check "$wall" --limit --json >"$name-before.json"
    "$after" check "$wall" --limit --json >"$name-after.json"
    cmp -s "$name-before.json" "$name-after.json" && echo "$name: identical" || echo "$name: differs"
done
echo "remove the scratch trees with: git worktree remove --force $work/before/tree; git worktree remove --force $work/after/tree"
