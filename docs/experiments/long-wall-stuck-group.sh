#!/usr/bin/env bash
# Reproduces the counts of docs/performance.md on long wall case 39 (10,005 blocks): how the
# stick-interval searches over 1,000 blocks or more end, and what repairing a certificate (a
# maximum flow at the limit) costs after a block is knocked out of the stuck group ("Long walls:
# the few decisions over the stuck group" and item 8 of "What could still be done").
#
# The counters and probes are temporary code, not part of pirqa: long-wall-stuck-group.patch,
# applied in a git worktree at the commit it was written against, prints one line per large
# search (SEARCH), per confirming flow (TIGHT) and per probe (PROBE) on stderr. The engine's
# results are those of the unpatched build.
#
#   bash docs/experiments/long-wall-stuck-group.sh [WORKDIR]     (about 15 minutes)
set -euo pipefail
source "$(dirname "$0")/scratch-tree.sh"
root=$(git rev-parse --show-toplevel)
work=${1:-/tmp/pirqa-long-wall-experiment}
base=eb8b10813163e03313b70830e65275da87688078
seconds=2.7
mkdir -p "$work"
cd "$root"

# The cases' walls and motions (the sweep writes them, then runs the case: case 39 about 2.5
# minutes).
for case in 24 39; do
    cargo run --release -- sweep walls/studies/long-walls.ron --case "$case" --out "$work/cases" \
        --no-history
done
case_dir="$work/cases/case-39"

# The decision logs, by the unpatched build: case 24 whole, case 39's first 6 s (145 of its
# 150 s), and what the decisions that take in 1,000 blocks or more cost.
shipped="$root/target/release/pirqa"
"$shipped" run "$work/cases/case-24/wall.ron" --record "$work/cases/case-24/motion.txt" \
    --duration 39.99 --out "$work/log-24" --no-history --decisions >/dev/null 2>&1
"$shipped" run "$case_dir/wall.ron" --record "$case_dir/motion.txt" --duration 6 \
    --out "$work/log-39" --no-history --decisions >/dev/null 2>&1
python3 - "$work/log-24/decisions.jsonl" "$work/log-39/decisions.jsonl" <<'PY'
import json, statistics, sys
for path in sys.argv[1:]:
    rows = [json.loads(line) for line in open(path)]
    cpu = sum(d["cpu_s"] for d in rows)
    big = [d for d in rows if d["blocks"] >= 1000]
    share = lambda ds: sum(d["cpu_s"] for d in ds) / cpu
    impacts = [d for d in big if d["cause"] == "impact"]
    on_stuck = [d for d in impacts if d.get("stuck_taken_in", {}).get("blocks", 0) >= 1000]
    stops = [d for d in big if d["cause"] == "stop"]
    print(path)
    print(f"  decisions {len(rows)}, of 1,000 blocks or more {len(big)} ({len(big) / len(rows):.1%}),"
          f" {share(big):.0%} of the decisions' {cpu:.1f} s")
    print(f"  impacts among them {len(impacts)}, median blocks {statistics.median(d['blocks'] for d in impacts):.0f},"
          f" {share(impacts):.0%}; on a stuck group of 1,000 or more {len(on_stuck)}; stops {share(stops):.0%}")
    # How far the ground acceleration is from the nearer limit of the stuck group taken in.
    near = []
    for d in rows:
        st = d.get("stuck_taken_in")
        if d["cause"] in ("impact", "stop", "meet", "touch") and st and st["blocks"] >= 1000:
            lo, hi, a = st["a_g_lo_m_s2"], st["a_g_hi_m_s2"], d["a_g_m_s2"]
            margin = min(a - lo if lo is not None else float("inf"), hi - a if hi is not None else float("inf"))
            width = hi - lo if lo is not None and hi is not None else None
            near.append((margin, d["cpu_s"], width))
    if near:
        far = [x for x in near if x[0] >= 0.1]
        widths = [x[2] for x in near if x[2] is not None]
        print(f"  changes to a stuck group of 1,000 or more: {len(near)}, {sum(x[1] for x in near):.1f} s;"
              f" margin to the nearer limit median {statistics.median(x[0] for x in near):.3f} m/s2,"
              f" interval width median {statistics.median(widths):.1f} m/s2;"
              f" 0.1 m/s2 or more away: {len(far)}, {sum(x[1] for x in far):.1f} s")
PY

scratch_tree "$work" "$base" docs/experiments/long-wall-stuck-group.patch
"$pirqa" run "$case_dir/wall.ron" --record "$case_dir/motion.txt" \
    --duration "$seconds" --out "$work/run" --no-history 2>"$work/counts.txt" >/dev/null

# q FRACTION: that quantile of the numbers on stdin (the value at rank ceil(f n)).
q() { sort -n | awk -v f="$1" '{ v[NR] = $1 } END { if (NR) { r = int(f * NR); if (r < f * NR) r++; if (r < 1) r = 1; print v[r] } }'; }
field() { sed -n "s/.* $1=\([0-9a-z]*\).*/\1/p"; }

echo "first ${seconds} s of case 39: $(grep -o '"flow_nodes": *[0-9]*' "$work/run/summary.json")"
searches=$(grep -c '^SEARCH' "$work/counts.txt" || true)
echo "searches over 1,000 blocks or more: $searches"
grep '^SEARCH' "$work/counts.txt" | awk '
    { split($2, n, "="); split($3, c, "="); nodes += n[2] * c[2] }
    $4 == "first_confirmed=true" { first++; first_nodes += n[2] }
    END { printf "  their cuts took in %d nodes; %d ended at a first cut that confirmed the ratio they started from (%d nodes)\n", nodes, first, first_nodes }'

echo "probes, all: $(grep -c '^PROBE' "$work/counts.txt"), blocks visited over the group's blocks, median: $(grep '^PROBE' "$work/counts.txt" | awk '{ split($2, n, "="); split($5, v, "="); print v[2] / n[2] }' | q 0.5)"
echo "probes: group | probes | no repair | blocks visited median (q1-q3) | paths median | blocks per path median"
echo "flows:  group | flows | joints at 99 % of capacity or more, median share | arcs to the ground full, median share"
for bin in "1000 1999" "2000 3999" "4000 6999" "7000 8999" "9000 10999"; do
    set -- $bin
    in_bin() { awk -v lo="$1" -v hi="$2" '{ split($2, n, "="); if (n[2] >= lo && n[2] <= hi) print }'; }
    probes=$(grep '^PROBE' "$work/counts.txt" | in_bin "$1" "$2")
    [ -n "$probes" ] || continue
    total=$(echo "$probes" | wc -l)
    failed=$(echo "$probes" | grep -c 'ok=false' || true)
    ok=$(echo "$probes" | grep 'ok=true')
    visited=$(echo "$probes" | field visited)
    per_path=$(echo "$ok" | awk '{ split($5, v, "="); split($6, p, "="); if (p[2] > 0) print v[2] / p[2] }')
    echo "  $1-$2 | $total | $failed | $(echo "$visited" | q 0.5) ($(echo "$visited" | q 0.25)-$(echo "$visited" | q 0.75)) | $(echo "$ok" | field paths | q 0.5) | $(echo "$per_path" | q 0.5)"
    flows=$(grep '^TIGHT' "$work/counts.txt" | in_bin "$1" "$2")
    tight=$(echo "$flows" | awk '{ split($5, j, "="); split($6, t, "="); print t[2] / j[2] }' | q 0.5)
    full=$(echo "$flows" | awk '{ split($3, g, "="); split($4, f, "="); print f[2] / g[2] }' | q 0.5)
    echo "  $1-$2 | $(echo "$flows" | wc -l) | $tight | $full"
done
echo "remove the scratch tree with: git worktree remove --force $tree"
