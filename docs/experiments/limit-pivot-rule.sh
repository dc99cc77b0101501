#!/usr/bin/env bash
# Reproduces the pivot-rule comparison of docs/rocking-walls.md (the limit at rest's cost, "The
# revised simplex"): the floating-point run of the limit programs with its rule as built
# (Dantzig's on scaled columns, Bland's after five degenerate pivots in a row) against Bland's
# rule throughout (STALL = 0 in src/limit/revised.rs, built in a scratch worktree):
#   1. `pirqa check --limit` on the Kancha enclosure and on a slender running bond of 6 courses,
#      timed;
#   2. the block-count study's case 16 (105 blocks, sampled friction) with --check-uplift,
#      stopped (SIGTERM) after 300 s: as built it ends checked to 39.99 s in about a minute;
#      with Bland's rule a program runs out of pivots, the exact tableau takes over and the
#      run is stopped, checked only to the state before.
# About 15 minutes.
#
#   bash docs/experiments/limit-pivot-rule.sh [WORKDIR]
set -euo pipefail
source "$(dirname "$0")/scratch-tree.sh"
work=${1:-/tmp/pirqa-limit-pivot-rule}
base=3e7614a
scratch_tree "$work/built" "$base"
built=$pirqa
scratch_tree "$work/bland" "$base" -c \
    "sed -i 's/^const STALL: usize = 5;\$/const STALL: usize = 0;/' src/limit/revised.rs &&
     grep -q '^const STALL: usize = 0;\$' src/limit/revised.rs"
bland=$pirqa
pirqa=$built
"$pirqa" generate --courses 6 --blocks-per-course 24 -o "$work/slender-6.ron" >/dev/null
"$pirqa" sweep walls/studies/block-count.ron --case 16 --out "$work/cases" --no-history >/dev/null
seconds() { python3 -c "print(round($(date +%s.%N) - $1, 2))"; }
for rule in built bland; do
    bin=$built
    [ "$rule" = bland ] && bin=$bland
    for wall in walls/inca/kancha-enclosure.ron "$work/slender-6.ron"; do
        start=$(date +%s.%N)
        "$bin" check "$wall" --limit >/dev/null
        echo "$rule: limit of $wall in $(seconds "$start") s"
    done
    dir="$work/cases/case-16"
    start=$(date +%s.%N)
    timeout -s TERM 300 "$bin" run "$dir/wall.ron" --record "$dir/motion.txt" --model slide \
        --duration 39.99 --out "$work/run-$rule" --no-history --check-uplift >/dev/null || true
    echo "$rule: case 16 checked in $(seconds "$start") s:" \
        "$(grep -o '"checked_until_s": [0-9.e+-]*' "$work/run-$rule/summary.json")"
done
echo "remove the scratch trees with: git worktree remove --force $work/built/tree; git worktree remove --force $work/bland/tree"
