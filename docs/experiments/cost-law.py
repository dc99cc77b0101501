"""How the CPU time per case of the block-count and long-wall studies follows the events and the
wall's height in courses (docs/block-count.md, "What it costs"). Reads the committed results
(docs/block-count/cases.csv and timing.csv, the same for docs/long-walls) and the study files
they came from (for each wall's courses); runs nothing.

    python3 docs/experiments/cost-law.py
"""

import csv
import math
import re
import statistics
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
STUDIES = [("block-count", "walls/studies/block-count.ron"), ("long-walls", "walls/studies/long-walls.ron")]


def courses_by_blocks(study_file):
    """Blocks -> courses of each generated wall: C courses of B blocks, every other course
    offset by half a block and so one block longer (C * B + C // 2 blocks)."""
    text = (ROOT / study_file).read_text()
    walls = re.findall(r"RunningBond\(courses:\s*(\d+),\s*blocks_per_course:\s*(\d+)", text)
    return {c * b + c // 2: c for c, b in ((int(c), int(b)) for c, b in walls)}


def fit(x, y):
    """Least-squares slope of y on x, and R^2."""
    mx, my = statistics.mean(x), statistics.mean(y)
    slope = sum((a - mx) * (b - my) for a, b in zip(x, y)) / sum((a - mx) ** 2 for a in x)
    residual = sum((b - my - slope * (a - mx)) ** 2 for a, b in zip(x, y))
    return slope, 1 - residual / sum((b - my) ** 2 for b in y)


for name, study_file in STUDIES:
    courses = courses_by_blocks(study_file)
    timing = {t["case"]: t["cpu_s"] for t in csv.DictReader(open(ROOT / "docs" / name / "timing.csv"))}
    rows = [
        {**r, "cpu_s": timing[r["case"]]}
        for r in csv.DictReader(open(ROOT / "docs" / name / "cases.csv"))
        if not r["error"]
    ]
    for label, keep in (("all walls", lambda b: True), ("below 10,000 blocks", lambda b: b < 10000)):
        cases = [r for r in rows if keep(int(r["blocks"]))]
        cpu = [math.log(float(r["cpu_s"])) for r in cases]
        events = [math.log(float(r["events"])) for r in cases]
        work = [e + math.log(courses[int(r["blocks"])]) for e, r in zip(events, cases)]
        print(f"{name}, {label} ({len(cases)} cases): CPU ~ events^%.2f (R2 %.3f),"
              f" CPU ~ (events x courses)^%.2f (R2 %.3f)" % (*fit(events, cpu), *fit(work, cpu)))
    for blocks in sorted(courses):
        cases = [r for r in rows if int(r["blocks"]) == blocks]
        per = statistics.median(
            float(r["cpu_s"]) / float(r["events"]) / courses[blocks] * 1e6 for r in cases
        )
        print(f"  {blocks} blocks, {courses[blocks]} courses: {per:.1f} microseconds per event"
              f" and course (median)")
