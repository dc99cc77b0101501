#!/usr/bin/env python3
"""Generated columns: 80 columns of two and three blocks (five proportions, four sets of
joint frictions, four strengths) under El Centro 1940 (0.6 to 1.8 g, 15 s) and under a 2 Hz
sine (0.5 to 1.5 g, 8 s), 160 exact runs, and how each ended. The counts of "the 80 generated
columns" in docs/rocking-walls.md come from here.

    python3 docs/rocking/generated-columns/columns.py            # from the repository's root
    PIRQA=path/to/pirqa python3 docs/rocking/generated-columns/columns.py OUT_DIR

Writes OUT_DIR/outcomes.csv (one row a run), by default into docs/rocking/generated-columns/;
the runs themselves go to a scratch folder and are removed. Compare two builds by diffing their
outcomes.csv.
"""
import concurrent.futures
import csv
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", ".."))
RECORD = os.path.join(ROOT, "records", "elcentro1940_IELC180_peer_dt0p01_g.AT2")
# (widths, heights) bottom first, centred on the widest; then (ground, lower, upper) friction.
SHAPES = [([1.0, 0.2], [0.5, 0.8]), ([0.8, 0.3], [0.6, 1.0]), ([1.0, 1.0, 0.2], [0.5, 0.5, 0.8]),
          ([0.9, 0.7, 0.25], [0.4, 0.6, 0.9]), ([1.2, 0.6, 0.3], [0.5, 0.5, 1.0])]
FRICTIONS = [(0.8, 0.8, 0.8), (0.4, 0.35, 0.8), (0.6, 0.6, 0.6), (0.5, 0.7, 0.9)]
MOTIONS = {
    "elcentro": ([0.6, 1.0, 1.4, 1.8], lambda g: ["--record", RECORD, "--pga", f"{g}g", "--duration", "15"]),
    "sine": ([0.5, 0.8, 1.1, 1.5], lambda g: ["--sine", f"{g}g", "--freq", "2", "--duration", "8"]),
}


def wall(k, widths, heights, friction):
    rows = []
    for i, (w, h) in enumerate(zip(widths, heights)):
        x = (max(widths) - w) / 2
        rows.append(f'(height_m: {h}, x_m: {x:.3f}, blocks: [(width_m: {w}, name: "D{i}")])')
    joints = {"D0/ground": friction[0]}
    for i in range(1, len(widths)):
        joints[f"D{i}/D{i - 1}"] = friction[min(i, 2)]
    listed = ", ".join(f'"{a}": {b}' for a, b in joints.items())
    return (f'(version: 1, name: "c{k}", thickness_m: 1.0, density_kg_m3: 2600, friction: 0.8, '
            f'joint_friction: {{{listed}}}, rows: [{", ".join(rows)}])')


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "docs", "rocking", "generated-columns")
    pirqa = os.environ.get("PIRQA")
    if not pirqa:
        subprocess.run(["cargo", "build", "--release", "--quiet"], cwd=ROOT, check=True)
        pirqa = os.path.join(ROOT, "target", "release", "pirqa")
    os.makedirs(out, exist_ok=True)
    with tempfile.TemporaryDirectory() as scratch:
        cases = []
        for name, (strengths, motion) in MOTIONS.items():
            k = 0
            for widths, heights in SHAPES:
                for friction in FRICTIONS:
                    for g in strengths:
                        path = os.path.join(scratch, f"{name}-c{k}.ron")
                        with open(path, "w") as f:
                            f.write(wall(k, widths, heights, friction))
                        cases.append((name, k, widths, friction, g, path, motion(g)))
                        k += 1

        def run(case):
            name, k, widths, friction, g, path, motion = case
            res = os.path.join(scratch, f"{name}-o{k}")
            r = subprocess.run([pirqa, "run", path, *motion, "--out", res], capture_output=True, text=True)
            row = {"motion": name, "case": k, "widths_m": " ".join(map(str, widths)),
                   "friction": " ".join(map(str, friction[:len(widths)])), "strength_g": g}
            if r.returncode != 0:
                return {**row, "outcome": "error", "time_s": "", "reason": r.stderr.strip()[-300:],
                        "residual_over_input": ""}
            with open(os.path.join(res, "summary.json")) as f:
                s = json.load(f)
            e = s["energy"]
            residual = abs(e["residual_j"]) / max(1.0, abs(e["input_j"]))
            if s.get("stopped_at_s"):
                outcome, time_s, reason = "stop", s["stopped_at_s"], s["warnings"][0]
            elif s.get("collapse"):
                outcome, time_s, reason = "fell", s["collapse"]["time_s"], ""
            else:
                outcome, time_s, reason = "end", s["duration_s"], ""
            return {**row, "outcome": outcome, "time_s": time_s, "reason": reason,
                    "residual_over_input": f"{residual:.1e}"}

        with concurrent.futures.ThreadPoolExecutor(os.cpu_count() or 1) as pool:
            rows = list(pool.map(run, cases))
    with open(os.path.join(out, "outcomes.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    for name in MOTIONS:
        counts = {}
        for r in rows:
            if r["motion"] == name:
                counts[r["outcome"]] = counts.get(r["outcome"], 0) + 1
        print(name, ", ".join(f"{n} {o}" for o, n in sorted(counts.items())))


if __name__ == "__main__":
    main()
