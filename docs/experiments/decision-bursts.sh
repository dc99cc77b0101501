#!/usr/bin/env bash
# Reproduces the counts of docs/performance.md, "Bursts of slow collisions at the stuck group":
# how the decisions that take in a large part of the wall (a tenth of its blocks or more) come in
# bursts, and how slow the collisions behind them are, in case 26 (976 blocks) and case 34
# (10,050 blocks) of the block-count study. It uses the shipped build and its decision log
# (`--decisions`), no patch (about 2 minutes).
#
#   bash docs/experiments/decision-bursts.sh [WORKDIR]
set -euo pipefail
root=$(git rev-parse --show-toplevel)
work=${1:-/tmp/pirqa-decision-bursts}
mkdir -p "$work"
cd "$root"
cargo build --release
pirqa="$root/target/release/pirqa"
for case in 26 34; do
    "$pirqa" sweep walls/studies/block-count.ron --case "$case" --out "$work/cases" --no-history
    dir="$work/cases/case-$case"
    "$pirqa" run "$dir/wall.ron" --record "$dir/motion.txt" --duration 39.99 \
        --out "$work/log-$case" --no-history --decisions >/dev/null 2>&1
done
python3 - "$work/log-26" 976 "$work/log-34" 10050 <<'PY'
import collections, json, sys
args = sys.argv[1:]
for path, blocks in zip(args[::2], map(int, args[1::2])):
    rows = [json.loads(line) for line in open(f"{path}/decisions.jsonl")]
    speed = collections.defaultdict(float)
    for line in open(f"{path}/events.jsonl"):
        e = json.loads(line)
        if e["kind"] == "impact":
            speed[e["time_s"]] = max(speed[e["time_s"]], e["approach_speed_m_s"])
    cpu = sum(d["cpu_s"] for d in rows)
    large = [d for d in rows if d["blocks"] * 10 >= blocks]
    burst, last = [], None
    for d in large:
        if last is not None and d["time_s"] - last < 1e-3:
            burst.append(d)
        last = d["time_s"]
    share = lambda ds: sum(d["cpu_s"] for d in ds)
    print(f"{blocks} blocks: {len(rows)} decisions, {cpu:.3f} s of CPU")
    print(f"  taking in a tenth of the wall or more: {len(large)}, {share(large):.3f} s,"
          f" median {sorted(d['blocks'] for d in large)[len(large) // 2]} blocks")
    print(f"  of them within 1 ms of the one before: {len(burst)}, {share(burst):.3f} s;"
          f" by cause: {dict(collections.Counter(d['cause'] for d in burst).most_common())}")
    impacts = [d for d in large if d["cause"] == "impact"]
    classes = collections.Counter()
    for d in impacts:
        v = speed[d["time_s"]]
        classes["< 0.1 mm/s" if v < 1e-4 else "< 1 mm/s" if v < 1e-3 else ">= 1 mm/s"] += 1
    print(f"  impacts among them: {len(impacts)}, {share(impacts):.3f} s; fastest approach at"
          f" their instant: {dict(sorted(classes.items()))}")
PY
