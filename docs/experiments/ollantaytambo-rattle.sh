#!/usr/bin/env bash
# Reproduces the trace and the first two trials of "The Ollantaytambo wall: fillers that never
# stop, handed back" in docs/rocking-walls.md: the Ollantaytambo wall under El Centro at 0.3 g
# with `--after-uplift moreau-while-rocking`, its fillers F2 and F5 traced step by step at
# 20.000-20.030 s, then run whole with the two stillness criteria that were tried and not kept,
# all on the commit before the criterion that hands the wall back (its stillness criterion is
# "shipped" below).
#
# The trace and the criteria are temporary code, not part of pirqa: ollantaytambo-rattle.patch,
# applied in a git worktree at the commit it was written against, reads PIRQA_TRACE=FROM,TO and
# PIRQA_TRACE_BLOCKS=NAMES (print each step's pose and velocity of those blocks) and
# PIRQA_STILL=mean|energy (unset: that commit's criterion). About 10 minutes with the build.
#
#   bash docs/experiments/ollantaytambo-rattle.sh [WORKDIR]
set -euo pipefail
source "$(dirname "$0")/scratch-tree.sh"
work=${1:-/tmp/pirqa-ollantaytambo-rattle}
scratch_tree "$work" beb4007c55f090d5785d89556a3c22a59fb99797 docs/experiments/ollantaytambo-rattle.patch

run() {
    "$pirqa" run walls/inca/ollantaytambo-monoliths.ron \
        --record records/elcentro1940_IELC180_peer_dt0p01_g.AT2 --pga 0.3g \
        --after-uplift moreau-while-rocking --dt 1e-3 --no-history "$@"
}
echo "F2 and F5, step by step (u, w: the centre's displacement and sinking, m; velocities m/s, rad/s):"
PIRQA_TRACE=20,20.03 PIRQA_TRACE_BLOCKS=F2,F5 run --duration 20.03 --out "$work/trace" 2>&1 \
    | grep '^trace'
for criterion in shipped mean energy; do
    PIRQA_STILL=$criterion run --out "$work/$criterion" >/dev/null 2>&1
    python3 - "$work/$criterion/summary.json" "$criterion" <<'PY'
import json, sys
why = json.load(open(sys.argv[1]))["model"]["why"]
print(f"{sys.argv[2]}: {why[why.index('stretches stepped'):][:100]}")
PY
done
