#!/usr/bin/env bash
# Reproduces item 9 of "What could still be done" in docs/performance.md: what the block-count
# study's cases 26 (976 blocks) and 34 (10,050 blocks) cost, and how their answers move, when
# collisions slower than a given approach speed are plastic (e = 0) instead of elastic.
#
# The threshold is temporary code, not part of pirqa: slow-impacts-plastic.patch, applied in a
# git worktree at the commit it was written against, reads it (m/s) from the environment
# variable PLASTIC_BELOW (unset or 0: the shipped model). About 3 minutes.
#
#   bash docs/experiments/slow-impacts-plastic.sh [WORKDIR]
set -euo pipefail
source "$(dirname "$0")/scratch-tree.sh"
work=${1:-/tmp/pirqa-slow-impacts}
scratch_tree "$work" 26887a432dd1196fcdaa7ff68c9401ebbdc66966 docs/experiments/slow-impacts-plastic.patch

for case in 26 34; do
    "$pirqa" sweep walls/studies/block-count.ron --case "$case" --out "$work/cases" --no-history
    dir="$work/cases/case-$case"
    for below in 0 1e-4 1e-3; do
        out="$work/run-$case-$below"
        mkdir -p "$out"
        /usr/bin/time -f "%e" -o "$out/seconds" env PLASTIC_BELOW="$below" "$pirqa" run \
            "$dir/wall.ron" --record "$dir/motion.txt" --duration 39.99 --out "$out" \
            --no-history --decisions >/dev/null 2>&1
    done
done
python3 - "$work" <<'PY'
import json, sys
work = sys.argv[1]
for case, blocks in ((26, 976), (34, 10050)):
    base = None
    for below in ("0", "1e-4", "1e-3"):
        out = f"{work}/run-{case}-{below}"
        s = json.load(open(f"{out}/summary.json"))
        rows = [json.loads(line) for line in open(f"{out}/decisions.jsonl")]
        large = [d for d in rows if d["blocks"] * 10 >= blocks]
        final = [b["final_displacement_m"] for b in s["blocks"]]
        base = base or final
        moved = max(abs(a - b) for a, b in zip(final, base))
        top = max(b["max_abs_displacement_m"] for b in s["blocks"])
        seconds = float(open(f"{out}/seconds").read())
        print(f"case {case} ({blocks} blocks), plastic below {below} m/s: {seconds:.2f} s,"
              f" events {s['stats']['events']}, decisions {len(rows)} ({len(large)} over a tenth"
              f" of the wall), collisions {s['impacts']}, flow nodes {s['stats']['flow_nodes']}"
              f" ({sum(d['flow_nodes'] for d in large)} in the large decisions),"
              f" max |u| {top * 1e3:.4f} mm, final displacements moved by at most"
              f" {moved * 1e6:.2g} micrometres")
PY
