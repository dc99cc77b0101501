#!/usr/bin/env bash
# Reproduces the times per factorisation of docs/rocking-walls.md, "Coulomb's LU in its
# supernodal form": every matrix Coulomb's Newton factorises is factorised ten times more, in
# faer's simplicial and in its supernodal form, by temporary code (newton-lu-forms.patch, at
# f414714, the build that made the supernodal form pirqa's); the mean time of each form and the
# matrices' count, printed every 1000 matrices (the last lines of each run shown). The slender
# 105-block running bond (400 gal 2 Hz sine, 0.1 s), the 17-block running bond (the same sine,
# 1 s, dt = 1.25e-4 s) and the Ollantaytambo wall (El Centro at 0.6 g, 15 s). About 10 minutes
# with the build.
#
#   bash docs/experiments/newton-lu-forms.sh [WORKDIR]
set -euo pipefail
source "$(dirname "$0")/scratch-tree.sh"
work=${1:-/tmp/pirqa-newton-lu-forms}
scratch_tree "$work" f414714 docs/experiments/newton-lu-forms.patch
"$pirqa" generate --courses 10 --blocks-per-course 10 --height 4.8m -o "$work/slender.ron" >/dev/null
"$pirqa" generate --courses 2 --blocks-per-course 8 -o "$work/bond-17.ron" >/dev/null
stepped="--model slide-rock --method moreau --contact-solver newton"
last() { grep '^TIMING' | tail -2; }
echo "slender 105-block bond:"
"$pirqa" run "$work/slender.ron" --sine 400gal --freq 2 --duration 0.1 $stepped --dt 1e-3 \
    --summary "$work/slender.json" 2>&1 | last
echo "17-block bond:"
"$pirqa" run "$work/bond-17.ron" --sine 400gal --freq 2 --duration 1 $stepped --dt 1.25e-4 \
    --summary "$work/bond-17.json" 2>&1 | last
echo "Ollantaytambo wall:"
"$pirqa" run walls/inca/ollantaytambo-monoliths.ron --record records/elcentro1940_IELC180_peer_dt0p01_g.AT2 \
    --pga 0.6g --duration 15 $stepped --dt 5e-4 --summary "$work/ollantaytambo.json" 2>&1 | last
echo "remove the scratch tree with: git worktree remove --force $tree"
