#!/usr/bin/env bash
# Reproduces the trial of docs/rocking-walls.md ("Keeping each group's centre of mass"): the
# Ollantaytambo wall under El Centro at 0.3 g, dt = 1e-3 s, stepped while it rocks with the
# set-down as shipped (each group of touching blocks placed from its first block) and with
# set-down-centre-of-mass.patch (a group free of abutments placed about its centre of mass),
# both against stepping to the end. Two scratch worktrees at the commit the patch was written
# against; about 12 minutes with the builds.
#
#   bash docs/experiments/set-down-centre-of-mass.sh [WORKDIR]
set -euo pipefail
source "$(dirname "$0")/scratch-tree.sh"
work=${1:-/tmp/pirqa-set-down-com}
base=648481c
scratch_tree "$work/shipped" "$base"
shipped=$pirqa
scratch_tree "$work/centre" "$base" docs/experiments/set-down-centre-of-mass.patch
centre=$pirqa
run() {
    "$1" run walls/inca/ollantaytambo-monoliths.ron \
        --record records/elcentro1940_IELC180_peer_dt0p01_g.AT2 --pga 0.3g \
        --after-uplift "$2" --dt 1e-3 --no-history --out "$work/$3" >/dev/null
}
run "$shipped" moreau end
run "$shipped" moreau-while-rocking first
run "$centre" moreau-while-rocking centre
python3 - "$work" <<'PY'
import json, math, sys
work = sys.argv[1]
runs = {k: {b["name"]: b for b in json.load(open(f"{work}/{k}/summary.json"))["blocks"]}
        for k in ("end", "first", "centre")}
end = runs["end"]
keys = [("final_displacement_m", "final u (m)"), ("max_abs_displacement_m", "largest u (m)"),
        ("max_abs_rotation_rad", "largest rotation (rad)")]
for key, label in keys:
    print(f"{label}: block, to the end, from the first block, about the centre of mass")
    for name in end:
        print(f"  {name}", *(f"{runs[k][name][key]:.3g}" for k in ("end", "first", "centre")))
    for k in ("first", "centre"):
        rms = math.sqrt(sum((runs[k][n][key] - end[n][key]) ** 2 for n in end) / len(end))
        print(f"  rms error against the end, {k}: {rms:.3g}")
PY
echo "remove the scratch trees with: git worktree remove --force $work/shipped/tree; git worktree remove --force $work/centre/tree"
