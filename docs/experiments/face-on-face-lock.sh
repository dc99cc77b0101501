#!/usr/bin/env bash
# Reproduces the figure of "A face that comes down flat on a face" in docs/rocking-walls.md: a
# lock of two bodies at rest face on face (both ends of the faces' overlap staying after a flat
# landing, each body on a stuck pivot) is reached by no scene of the rocking scans.
#
# The lock is temporary code, not part of pirqa: face-on-face-lock.patch, applied in a git
# worktree at the commit it was written against (a new module `lock.rs`: the two pushes and the
# pivots' forces from statics, the pushes >= 0 as the rest's conditions, a couple on the other
# end where one falls to zero). It runs the scans (docs/rocking/scans/scan.sh) and compares them
# with that commit's: every run the lock does not reach ends as before, and the stops where both
# ends stay say why the lock was not entered. About 8 minutes (most of it the build).
#
#   bash docs/experiments/face-on-face-lock.sh [WORKDIR]
set -euo pipefail
source "$(dirname "$0")/scratch-tree.sh"
work=${1:-/tmp/pirqa-face-on-face-lock}
base=3a7c78591e106332697dad2239d27959037131d0
scratch_tree "$work" "$base" docs/experiments/face-on-face-lock.patch
(cd "$tree" && PIRQA="$pirqa" bash docs/rocking/scans/scan.sh "$work/scan" > /dev/null)
git show "$base:docs/rocking/scans/outcomes.csv" > "$work/before.csv"
python3 - "$work" <<'PY'
import collections, csv, sys
work = sys.argv[1]
before = list(csv.DictReader(open(f"{work}/before.csv")))
after = list(csv.DictReader(open(f"{work}/scan/outcomes.csv")))
assert len(before) == len(after)
changed, why = 0, collections.Counter()
for b, a in zip(before, after):
    if any(b[k] != a[k] for k in b if k != "detail"):
        changed += 1
    if "both ends of their contact stay" in b["detail"]:
        why[a["detail"].split(" N s)")[-1].strip(", ")] += 1
    elif b["detail"] != a["detail"]:
        changed += 1
print(f"{len(after)} runs; runs whose outcome, end or energy changed: {changed}")
print(f"stops where both ends stay: {sum(why.values())}, now saying:")
for text, n in why.most_common():
    print(f"  {n:3d}  {text}")
print("runs that rested locked:", sum("rest locked" in a["detail"] for a in after))
PY
