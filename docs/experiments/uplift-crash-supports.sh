#!/usr/bin/env bash
# Reproduces the times before and after the exact check's pivots reciprocals, its feasibility
# from the vertex's signs and the crash that judges a split by its supports (docs/rocking-walls.md,
# "The crash judges a split by its supports"): the build before (566f130) and the build with
# all three (0c7eaf5) on the eight 105-block cases with --check-uplift, side by side
# (uplift-two-builds.sh), then on the runs of the uplift check's table of findings and the
# 18-block cases 8 and 12 (uplift-findings.sh). About 25 minutes with the two builds.
#
#   bash docs/experiments/uplift-crash-supports.sh [WORKDIR]
set -euo pipefail
work=${1:-/tmp/pirqa-uplift-crash-supports}
bash "$(dirname "$0")/uplift-two-builds.sh" 566f130 0c7eaf5 "$work"
bash "$(dirname "$0")/uplift-findings.sh" 566f130 0c7eaf5 "$work"
