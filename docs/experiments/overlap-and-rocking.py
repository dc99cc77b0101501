"""Do the exact sliding runs that warn of lost overlap pick out the cases that rock once blocks
may turn? Reads two finished sweeps of the same cases: the exact sliding one (fragility.ron)
and the time-stepped one with every block's rotation (fragility-moreau.ron), and prints per
level how many cases lost a tenth or more of some joint's overlap sliding, how many stood and
turned a block by more than 0.01 rad time stepped, and how many did both.

    pirqa sweep walls/studies/fragility.ron --out out/fragility
    pirqa sweep walls/studies/fragility-moreau.ron --out out/fragility-moreau   # 18 min on 2 cores
    python3 docs/experiments/overlap-and-rocking.py out/fragility out/fragility-moreau
"""

import csv
import sys
from collections import defaultdict


def rows(folder):
    with open(f"{folder}/cases.csv") as f:
        return {r["case"]: r for r in csv.DictReader(f)}


sliding, turning = rows(sys.argv[1]), rows(sys.argv[2])
levels = defaultdict(lambda: [0, 0, 0, 0])
for case, s in sliding.items():
    t = turning[case]
    beyond = float(s["max_overlap_loss"]) >= 0.1
    rocked = t["collapsed"] == "false" and float(t["max_abs_rotation_rad"]) > 0.01
    level = levels[round(float(s["pga_gal"]))]
    level[0] += 1
    level[1] += beyond
    level[2] += rocked
    level[3] += beyond and rocked
print("pga_gal cases beyond_small turned_over_0.01_rad_standing both")
for pga, (n, beyond, rocked, both) in sorted(levels.items()):
    print(pga, n, beyond, rocked, both)
total = [sum(v[i] for v in levels.values()) for i in range(4)]
print("all", *total)
