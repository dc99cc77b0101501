#!/usr/bin/env bash
# Reproduces the times before and after the watch asks only whether a state stays seated at its
# stick limits (docs/rocking-walls.md, "Seated at the stick limits"): the build before
# (6efed0c) and the build with it (527dee0) on the eight 105-block cases with --check-uplift,
# side by side (uplift-two-builds.sh), then both on the runs of the uplift check's table of
# findings (where the check finds an uplift, and so solves intervals to their ends), each run's
# summary.json and events.jsonl compared, and the 18-block cases 8 and 12, each build twice,
# timed and compared. About 25 minutes with the two builds.
#
#   bash docs/experiments/uplift-seated-at.sh [WORKDIR]
set -euo pipefail
work=${1:-/tmp/pirqa-uplift-seated-at}
bash "$(dirname "$0")/uplift-two-builds.sh" 6efed0c 527dee0 "$work"
source "$(dirname "$0")/scratch-tree.sh"
scratch_builds "$work" 6efed0c 527dee0
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
