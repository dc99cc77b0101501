#!/usr/bin/env bash
# Reproduces the times of "The limit at rest from the crash too" (docs/rocking-walls.md): the
# build before (6904433: the limit at rest from the artificial basis, up to 1000 blocks) against
# d315d36 (from the crash), `pirqa check W --limit --json` timed on walls up to 976 blocks, each
# pair side by side on the two cores, outputs compared but for `mechanism_unique` (the field
# d315d36 added; `mechanism_uniqueness`, decided exactly, since b8e7ae7); then walls
# beyond the old bound on d315d36 alone, one after the other, and on a third build of it with
# the bound raised to 8000 a long wall of 3,165 blocks and a bond of 4,000. About 40 minutes
# with the three builds (the 4,000-block bond alone takes about 9).
#
#   bash docs/experiments/limit-from-crash.sh [WORKDIR]
set -euo pipefail
source "$(dirname "$0")/scratch-tree.sh"
work=${1:-/tmp/pirqa-limit-from-crash}
scratch_builds "$work" 6904433 d315d36
scratch_tree "$work/raised" d315d36 -c \
    "sed -i 's/^pub const MAX_BLOCKS: usize = 2000;\$/pub const MAX_BLOCKS: usize = 8000;/' src/limit/mod.rs &&
     grep -q '^pub const MAX_BLOCKS: usize = 8000;\$' src/limit/mod.rs"
raised=$pirqa
cd "$work"

# name build binary wall: one timed check, its JSON in name-build.json.
timed() {
    /usr/bin/time -f "$1, $2: %e s, %M KB" "$3" check "$4" --limit --json >"$1-$2.json"
}
# The limits and mechanisms, without the flag the build before does not write.
limits() { grep -v '"mechanism_unique"' "$1" | sed 's/^\( *\]\),$/\1/'; }
# name wall: both builds side by side, then whether they say the same.
pair() {
    timed "$1" before "$before" "$2" &
    timed "$1" after "$after" "$2" &
    wait
    if cmp -s <(limits "$1-before.json") <(limits "$1-after.json"); then
        echo "$1: same limits and mechanisms"
    else
        echo "$1: differs (mechanism_unique: $(grep -o 'unique": [a-z]*' "$1-after.json" | tr '\n' ' '))"
    fi
}

"$after" generate --blocks 250 -o bond-250.ron
"$after" generate --courses 10 --blocks-per-course 40 -o slender-10.ron
"$after" generate --blocks 500 -o bond-500.ron
"$after" generate --courses 14 --blocks-per-course 56 -o slender-14.ron
"$after" generate --blocks 1000 -o bond-1000.ron
"$after" generate --courses 20 --blocks-per-course 80 -o slender-20.ron
"$after" generate --blocks 2000 -o bond-2000.ron
"$after" generate --blocks 4000 -o bond-4000.ron
"$after" sweep "$root/walls/studies/block-count.ron" --case 24 --no-history --out bc >/dev/null
"$after" sweep "$root/walls/studies/long-walls.ron" --case 17 --no-history --out lw >/dev/null
"$after" sweep "$root/walls/studies/long-walls.ron" --case 25 --no-history --out lw >/dev/null

for wall in "$root"/walls/*.ron "$root"/walls/inca/*.ron "$root"/walls/rocking/*.ron; do
    pair "$(basename "$wall" .ron)" "$wall" 2>/dev/null
done
for wall in bond-250 slender-10 bond-500 slender-14 bond-1000; do
    pair "$wall" "$wall.ron"
done
pair block-count-24 bc/case-24/wall.ron
timed long-wall-17 after "$after" lw/case-17/wall.ron
timed slender-20 after "$after" slender-20.ron
timed bond-2000 after "$after" bond-2000.ron
timed long-wall-25 raised "$raised" lw/case-25/wall.ron
timed bond-4000 raised "$raised" bond-4000.ron
echo "remove the scratch trees with: for t in before after raised; do git worktree remove --force $work/\$t/tree; done"
