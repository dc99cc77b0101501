#!/usr/bin/env bash
# Reproduces the warm-start trial of docs/rocking-walls.md (the uplift check's Cost): each state's
# two programs started from the bases that proved the state before (and the +x side from the -x
# side's basis), their columns pivoted in place of artificial variables, then the primal simplex
# where that basis is feasible and the dual simplex where its reduced costs are non-negative
# (both with Bland's rule), the run from the artificial basis where neither.
#   1. the block-count study's case 12 (18 blocks, sampled friction) with --check-uplift, from
#      the artificial basis (PIRQA_COLD=1) and warm, alternating, timed; then how each warm
#      start went (primal, dual, neither) and the cold runs' pivots;
#   2. its case 16 (105 blocks) warm for 120 s: every run's pivots.
#
# The trial code is temporary, not part of pirqa: limit-warm-start.patch, applied in a git
# worktree at the commit it was written against, adds the warm start, prints a TRACE line per
# run, and keeps the runs cold where PIRQA_COLD is set. About 8 minutes.
#
#   bash docs/experiments/limit-warm-start.sh [WORKDIR]
set -euo pipefail
source "$(dirname "$0")/scratch-tree.sh"
work=${1:-/tmp/pirqa-limit-warm}
scratch_tree "$work" bb69292 docs/experiments/limit-warm-start.patch

for case in 12 16; do
    "$pirqa" sweep walls/studies/block-count.ron --case "$case" --out "$work/cases-$case" \
        --no-history >/dev/null
done
run() { # case, extra environment, time limit
    local dir="$work/cases-$1/case-$1"
    env $2 timeout -s TERM "$3" "$pirqa" run "$dir/wall.ron" --record "$dir/motion.txt" \
        --model slide --duration 39.99 --out "$work/run-$1" --no-history --check-uplift \
        2>"$work/trace-$1" >/dev/null || true
}
for round in 1 2; do
    for how in PIRQA_COLD=1 PIRQA_WARM=1; do
        start=$(date +%s.%N)
        run 12 "$how" 300
        echo "case 12, $how: $(python3 -c "print(round($(date +%s.%N) - $start, 2))") s"
    done
done
grep TRACE "$work/trace-12" | sed 's/[0-9]\+ pivots/N pivots/; s/neither.*/neither/' | sort | uniq -c
run 16 PIRQA_WARM=1 120
grep TRACE "$work/trace-16"
