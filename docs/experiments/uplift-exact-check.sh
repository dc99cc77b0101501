#!/usr/bin/env bash
# Reproduces where the uplift check's time went before its exact check factorised a basis once
# (docs/rocking-walls.md, "One factorisation for a basis and its transpose"): the block-count
# study's case 19 (105 blocks, sampled friction, El Centro at 400 gal) with --check-uplift, by
# the build before (c44a666) with temporary timing (uplift-exact-check.patch): each program's
# floating-point run and exact check, and each elimination in the exact checks with the largest
# answer's bits, summed here. About 8 minutes with the build.
#
#   bash docs/experiments/uplift-exact-check.sh [WORKDIR]
set -euo pipefail
source "$(dirname "$0")/scratch-tree.sh"
work=${1:-/tmp/pirqa-uplift-exact-check}
scratch_tree "$work" c44a666 docs/experiments/uplift-exact-check.patch
"$pirqa" sweep walls/studies/block-count.ron --case 19 --no-history --out "$work/bc" >/dev/null
dir="$work/bc/case-19"
/usr/bin/time -f "whole run: %e s" "$pirqa" run "$dir/wall.ron" --record "$dir/motion.txt" \
    --model slide --duration 39.99 --check-uplift --no-history --out "$work/run" \
    2>"$work/timing.txt" >/dev/null
tail -1 "$work/timing.txt"
awk '$1 == "TIMING" && $2 == "floating" { n++; f += $3; x += $5 }
     $1 == "TIMING" && $2 == "eliminate" { e += $3; k++; if ($5 > b) b = $5; if (!lo || $5 < lo) lo = $5 }
     END { printf "programs %d: floating-point runs %.1f s, exact checks %.1f s, of which %d eliminations %.1f s; largest answers %d-%d bits\n", n, f, x, k, e, lo, b }' \
    "$work/timing.txt"
echo "remove the scratch tree with: git worktree remove --force $tree"
