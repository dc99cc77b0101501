"""How many blocks the exact engine's decisions take in on a stack of C blocks (one per course),
against C: the wall where exactness alone would allow a decision in O(log^2 C) and the engine,
deciding each stuck part afresh, reads a share of it (docs/performance.md, "Does exactness
force the cost per event to grow with the courses?"). Writes the stacks (blocks 1.0 x 0.25 m,
each bed joint's friction drawn from 0.25-0.35 with a fixed seed per size) to a scratch folder
and runs each under the 400 gal, 1 Hz sine for 40 s, sliding only.

    python3 docs/experiments/stack-decisions.py target/release/pirqa
"""

import json
import random
import subprocess
import sys
import tempfile
from pathlib import Path


def stack(c):
    """The RON wall of a stack of `c` blocks, its joints' friction drawn with seed `c`."""
    rnd = random.Random(c)
    rows = ",\n".join(
        f'        (height_m: 0.25, blocks: [(width_m: 1.0, name: "S{k + 1}")])' for k in range(c)
    )
    joints = [f'        "S1/ground": {rnd.uniform(0.25, 0.35):.4f}'] + [
        f'        "S{k + 1}/S{k}": {rnd.uniform(0.25, 0.35):.4f}' for k in range(1, c)
    ]
    joints = ",\n".join(joints)
    return f"""(
    version: 1,
    name: "Stack of {c}",
    thickness_m: 0.8,
    density_kg_m3: 2650,
    friction: 0.30,
    restitution: 1.0,
    rows: [
{rows}
    ],
    joint_friction: {{
{joints}
    }},
)
"""


def main():
    pirqa = sys.argv[1] if len(sys.argv) > 1 else "target/release/pirqa"
    print("courses  events  decisions  blocks taken in  per decision")
    with tempfile.TemporaryDirectory() as scratch:
        for c in (10, 20, 40, 80, 160):
            wall = Path(scratch) / f"stack{c}.ron"
            wall.write_text(stack(c))
            summary = Path(scratch) / f"stack{c}.json"
            subprocess.run(
                [pirqa, "run", str(wall), "--model", "slide", "--sine", "400gal", "--freq", "1",
                 "--duration", "40", "--summary", str(summary)],
                check=True, stdout=subprocess.DEVNULL,
            )
            stats = json.loads(summary.read_text())["stats"]
            per = stats["decision_blocks"] / stats["mode_decisions"]
            print(f"{c:7d}  {stats['events']:6d}  {stats['mode_decisions']:9d}  "
                  f"{stats['decision_blocks']:15d}  {per:12.1f}")


if __name__ == "__main__":
    main()
