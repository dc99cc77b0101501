#!/usr/bin/env bash
# Reproduces the figure of docs/reliability.md on events that crowd in: a slab between a wall and
# a squat block (restitution 0.8, run 1156 of docs/rocking/scans) whose face comes down flat on
# the wall's again and again in a couple, at 1e-10 m/s, once the ends of flat landings that have
# not parted by more than round-off rebound again (the rule of docs/rocking-walls.md, "Faces that
# meet from apart", undone). The run then stops with the EventsCrowd error in about 2 s instead
# of running for ever. The change is temporary, made by two edits of clearance.rs in a git
# worktree at the commit the script was written against. About 3 minutes (most of it the build).
#
#   bash docs/experiments/flat-rebounds.sh [WORKDIR]
set -euo pipefail
source "$(dirname "$0")/scratch-tree.sh"
work=${1:-/tmp/pirqa-flat-rebounds}
base=246fc66031deb3a8b7815485dcb1bb84163b3135
undo='f=src/integrate/rocking/clearance.rs
sed -i "s/(pa, pb), 0.5 \* x) <= self.tie_m(k);/(pa, pb), 0.5 * x) <= self.tie_m(k) \&\& false;/" $f
sed -i "s/ends.map(|t| Touch { stays, ..t })/ends.map(|t| Touch { stays: false, ..t })/" $f
[ "$(grep -c "tie_m(k) && false;" $f)" = 1 ] && grep -q "stays: false, ..t" $f'
scratch_tree "$work" "$base" -c "$undo"
cat > "$work/wall.ron" <<'RON'
(version: 1, thickness_m: 0.5, density_kg_m3: 2500, friction: 0.5, restitution: 0.8,
 rows: [(height_m: 1.2, blocks: [(width_m: 0.6, name: "W"), (width_m: 0.25, gap_m: 0.02,
 name: "S"), (width_m: 1.0, height_m: 0.8, gap_m: 0.02, name: "T")])])
RON
for bin in "$pirqa" "$root/target/release/pirqa"; do
    [ -x "$bin" ] || (cd "$root" && cargo build --release --quiet)
    echo "== $bin"
    /usr/bin/time -f "%e s" timeout 600 "$bin" run "$work/wall.ron" --sine 0.45g --freq 2 \
        --phase 270 --duration 15 --out "$work/out" 2>&1 | grep -E "^error|warning|^[0-9.]+ s$" \
        | cut -c1-240 || true
done
