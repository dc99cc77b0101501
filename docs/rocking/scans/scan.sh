#!/usr/bin/env bash
# Sweeps of small rocking scenes: every run of five grids of walls and motions, and how each
# ended (to its duration, at an overturning, at a meeting the exact model stops at, or in an
# error). The figures quoted in docs/model.md (section 8), docs/rocking-walls.md and
# src/integrate/rocking/tie_tests.rs come from here.
#
#   bash docs/rocking/scans/scan.sh            # from the repository's root; about 2 minutes
#   PIRQA=path/to/pirqa bash docs/rocking/scans/scan.sh OUT_DIR   # another build, elsewhere
#
# Writes OUT_DIR/outcomes.csv (one row a run) and OUT_DIR/summary.csv (counts a grid), by
# default into docs/rocking/scans/. The runs themselves go to a scratch folder and are removed.
set -euo pipefail
cd "$(dirname "$0")/../../.."
out=${1:-docs/rocking/scans}
if [ -z "${PIRQA:-}" ]; then
    cargo build --release --quiet
    PIRQA=target/release/pirqa
fi
record=records/elcentro1940_IELC180_peer_dt0p01_g.AT2
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
mkdir -p "$out"
list="$scratch/runs.tsv"
: > "$list"

# One run: grid name, wall text, duration (s), then the motion's options.
scene() {
    local grid=$1 wall=$2 duration=$3
    shift 3
    local n
    n=$(($(wc -l < "$list") + 1))
    local dir="$scratch/$n"
    mkdir -p "$dir"
    printf '%s\n' "$wall" > "$dir/wall.in.ron"
    local rc=0
    "$PIRQA" run "$dir/wall.in.ron" "$@" --duration "$duration" --out "$dir/out" \
        > /dev/null 2> "$dir/stderr" || rc=$?
    rm -f "$dir"/out/history.csv "$dir"/out/response.*
    printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$n" "$grid" "$rc" "$duration" "$*" \
        "$(tr '\n' ' ' < "$dir/wall.in.ron")" >> "$list"
}

wall() { # friction, restitution, the row's blocks
    printf '(version: 1, thickness_m: 0.5, density_kg_m3: 2500, friction: %s, restitution: %s,\n' \
        "$1" "$2"
    printf ' rows: [(height_m: 1.2, blocks: [%s])])' "$3"
}

# A slab 0.3 x 1.2 m, a block W beside it (plastic landings), under sines: 576 runs.
for w in 0.5 0.6 0.7 0.8 1.0 1.2; do for h in 1.2 0.9; do for f in 0.6 0.9; do
for gap in 0.05 0.15; do for a in 0.3 0.4 0.5 0.6; do for hz in 1 1.5 2.5; do
    scene slab-block "$(wall $f 0.0 "(width_m: 0.3, name: \"S\"), \
(width_m: $w, height_m: $h, gap_m: $gap, name: \"W\")")" 4 --sine "${a}g" --freq $hz
done; done; done; done; done; done

# The same with landings that keep half or all of the rate (Housner's r from 0.5 to 1): 384 runs.
for r in 0.5 1.0; do for w in 0.5 0.6 0.8 1.2; do for h in 1.2 0.9; do for f in 0.6 0.9; do
for gap in 0.05 0.15; do for a in 0.3 0.5; do for hz in 1 1.5 2.5; do
    scene slab-block-restitution "$(wall $f $r "(width_m: 0.3, name: \"S\"), \
(width_m: $w, height_m: $h, gap_m: $gap, name: \"W\")")" 4 --sine "${a}g" --freq $hz
done; done; done; done; done; done; done

# Three blocks apart: W, a slab S, a squat block T 1.0 x 0.8 m, under El Centro and sines: 288.
for r in 0.0 0.3 0.8; do for sw in 0.25 0.4; do for w in 0.6 0.9 1.2; do for f in 0.5 0.8; do
for gap in 0.02 0.1; do
    blocks="(width_m: $w, name: \"W\"), (width_m: $sw, gap_m: $gap, name: \"S\"), \
(width_m: 1.0, height_m: 0.8, gap_m: $gap, name: \"T\")"
    for pga in 0.3g 0.6g; do
        scene three-blocks "$(wall $f $r "$blocks")" 15 --record $record --pga $pga
    done
    scene three-blocks "$(wall $f $r "$blocks")" 15 --sine 0.35g --freq 1.2 --phase 90
    scene three-blocks "$(wall $f $r "$blocks")" 15 --sine 0.45g --freq 2 --phase 270
done; done; done; done; done

# A slab beside a short slender block T, friction up to 2 (Painleve's paradox): 324 runs.
for r in 0.0 0.4 1.0; do for f in 0.4 0.7 2.0; do for th in 0.6 0.8 1.0; do for tw in 0.2 0.35; do
for gap in 0.1 0.5; do
    blocks="(width_m: 0.3, name: \"S\"), (width_m: $tw, height_m: $th, gap_m: $gap, name: \"T\")"
    scene slab-short-block "$(wall $f $r "$blocks")" 8 --sine 0.4g --freq 1 --phase 180
    scene slab-short-block "$(wall $f $r "$blocks")" 8 --sine 0.5g --freq 1.7
    scene slab-short-block "$(wall $f $r "$blocks")" 8 --sine 0.3g --freq 0.8 --phase 60
done; done; done; done; done

# A slab touching a block W, the two seated face on face from the start (--model slide-rock:
# auto slides such walls), under sines and El Centro: 96 runs.
for r in 0.0 0.5; do for w in 0.5 0.8 1.2; do for h in 1.2 0.9; do for f in 0.6 0.9; do
    blocks="(width_m: 0.3, name: \"S\"), (width_m: $w, height_m: $h, name: \"W\")"
    for motion in "--sine 0.3g --freq 1" "--sine 0.5g --freq 2.5" "--sine 0.4g --freq 1.5"; do
        # shellcheck disable=SC2086
        scene slab-touching-block "$(wall $f $r "$blocks")" 4 $motion --model slide-rock
    done
    scene slab-touching-block "$(wall $f $r "$blocks")" 15 --record $record --pga 0.4g \
        --model slide-rock
done; done; done; done

python3 - "$scratch" "$out" <<'PY'
import csv, json, os, re, sys
from collections import Counter, defaultdict

scratch, out = sys.argv[1:3]
rows = []
for line in open(os.path.join(scratch, "runs.tsv")):
    n, grid, rc, duration, motion, wall = line.rstrip("\n").split("\t")
    run = os.path.join(scratch, n)
    uplifts, residual = 0, ""
    if rc != "0":
        err = open(os.path.join(run, "stderr")).read()
        first = next((l for l in err.splitlines() if "error" in l.lower() or "panicked" in l),
                     err.strip().splitlines()[-1] if err.strip() else "no message")
        outcome, detail, ended = "error", first.strip().removeprefix("error: "), ""
    else:
        s = json.load(open(os.path.join(run, "out", "summary.json")))
        ended = s["duration_s"]
        e = s["energy"]
        # The balance's residual against the energies in it (a wall that never moved has none).
        scale = sum(abs(e[k]) for k in ("input_j", "friction_j", "impact_loss_j", "kinetic_j",
                                         "potential_j", "fallen_j"))
        residual = abs(e["residual_j"]) / scale if scale > 0 else abs(e["residual_j"])
        with open(os.path.join(run, "out", "events.jsonl")) as events:
            uplifts = sum(1 for e in events if '"kind":"uplift"' in e and "in the contact of" in e)
        if s.get("collapse"):
            c = s["collapse"]
            outcome, detail = "collapse", f'{c["block"]} {c["cause"]}'
        elif ended < float(duration):
            outcome = "stopped at a meeting"
            # The reason, without the instant, the modes tried and what the model follows.
            detail = re.sub(r"^.*? at t = [0-9.e+-]+ s, (and )?", "", s["warnings"][-1])
            detail = re.sub(r" \([^()]*would[^()]*\)", "", detail.split(": the exact model")[0])
        else:
            outcome, detail = "to the end", ""
    rows.append(dict(run=int(n), grid=grid, outcome=outcome, detail=detail, ended_s=ended,
                     energy_residual_of_energies=residual,
                     uplifts_of_seated_members_in_contact=uplifts, motion=motion, wall=wall))

with open(os.path.join(out, "outcomes.csv"), "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0]))
    w.writeheader()
    w.writerows(rows)

grids = defaultdict(Counter)
for r in rows:
    g = grids[r["grid"]]
    g["runs"] += 1
    g[r["outcome"]] += 1
    g["uplifts of seated members in contact"] += r["uplifts_of_seated_members_in_contact"]
    if r["energy_residual_of_energies"] != "":
        worst = max(float(g.get("largest energy residual (of the energies)", 0)),
                    r["energy_residual_of_energies"])
        g["largest energy residual (of the energies)"] = f"{worst:.1e}"
    if r["outcome"] in ("stopped at a meeting", "error"):
        # Errors grouped by their words, their numbers (instants, rates) left out.
        g[f'{r["outcome"]}: {re.sub(r"-?[0-9][0-9.e+-]*", "#", r["detail"])}'] += 1
with open(os.path.join(out, "summary.csv"), "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["grid", "count", "runs"])
    for grid, counts in grids.items():
        for what, k in counts.items():
            w.writerow([grid, what, k])
            print(f"{grid:24} {k:>7}  {what}")
PY
