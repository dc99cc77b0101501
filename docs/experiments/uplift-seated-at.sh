#!/usr/bin/env bash
# Reproduces the times before and after the watch asks only whether a state stays seated at its
# stick limits (docs/rocking-walls.md, "Seated at the stick limits"): the build before
# (6efed0c) and the build with it (527dee0) on the eight 105-block cases with --check-uplift,
# side by side (uplift-two-builds.sh), then both on the runs of the uplift check's table of
# findings (where the check finds an uplift, and so solves intervals to their ends), each run's
# summary.json and events.jsonl compared, and the 18-block cases 8 and 12, each build twice,
# timed and compared. About 25 minutes with the two builds.
#
#   bash docs/experiments/uplift-seated-at.sh [WORKDIR]
set -euo pipefail
work=${1:-/tmp/pirqa-uplift-seated-at}
bash "$(dirname "$0")/uplift-two-builds.sh" 6efed0c 527dee0 "$work"
bash "$(dirname "$0")/uplift-findings.sh" 6efed0c 527dee0 "$work"
