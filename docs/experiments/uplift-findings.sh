#!/usr/bin/env bash
# The uplift check of two builds on the runs of its table of findings (docs/rocking-walls.md:
# where the check finds an uplift, and so solves intervals to their ends), each run's
# summary.json and events.jsonl compared, then the block-count study's 18-block cases 8 and
# 12, each build twice, timed and compared. The builds are those of uplift-two-builds.sh (it
# reuses their scratch trees in WORKDIR when they are there). The scripts that quote it pass
# their commits.
#
#   bash docs/experiments/uplift-findings.sh BEFORE AFTER WORKDIR
set -euo pipefail
source "$(dirname "$0")/scratch-tree.sh"
first=$1 second=$2 work=$3
scratch_builds "$work" "$first" "$second"
cd "$work"
elcentro="$root/records/elcentro1940_IELC180_peer_dt0p01_g.AT2"
runs=(
    "walls/five-block-variable.ron --record $elcentro --pga 1.5g"
    "walls/inca/ollantaytambo-monoliths.ron --record $elcentro --pga 0.5g"
    "walls/inca/ollantaytambo-monoliths.ron --record $elcentro --pga 1.5g"
    "walls/inca/ollantaytambo-monoliths.ron --record $elcentro --pga 3g"
    "walls/rocking/slender-on-stack.ron --record $elcentro --pga 0.5g"
    "walls/rocking/dragged-block.ron --sine 0.7g --freq 1 --duration 2"
)
for k in "${!runs[@]}"; do
    read -r -a args <<<"${runs[$k]}"
    for build in before after; do
        bin=$before
        [ "$build" = after ] && bin=$after
        (cd "$root" && "$bin" run "${args[@]}" --model slide --check-uplift --no-history \
            --out "$work/found-$k-$build" >/dev/null)
    done
    cmp "found-$k-before/summary.json" "found-$k-after/summary.json" &&
        cmp "found-$k-before/events.jsonl" "found-$k-after/events.jsonl" &&
        echo "${runs[$k]%% *}: identical"
done
for case in 8 12; do
    "$after" sweep "$root/walls/studies/block-count.ron" --case "$case" --no-history --out "bc-$case" >/dev/null
    dir="bc-$case/case-$case"
    for round in 1 2; do
        for build in before after; do
            bin=$before
            [ "$build" = after ] && bin=$after
            /usr/bin/time -f "case $case, $build: %e s" "$bin" run "$dir/wall.ron" --record "$dir/motion.txt" \
                --model slide --duration 39.99 --check-uplift --no-history --out "$dir-$build" >/dev/null
        done
    done
    cmp "$dir-before/summary.json" "$dir-after/summary.json" &&
        cmp "$dir-before/events.jsonl" "$dir-after/events.jsonl" && echo "case $case: identical"
done
