#!/usr/bin/env bash
# Reproduces the uplift check's times before and after Lehmer's gcd (docs/rocking-walls.md,
# "The uplift check's exact arithmetic"): the build before (16c23e5) and the build with it
# (e930860) on the eight 105-block cases, side by side (uplift-two-builds.sh). About 25
# minutes with the two builds.
#
#   bash docs/experiments/uplift-gcd.sh [WORKDIR]
set -euo pipefail
exec bash "$(dirname "$0")/uplift-two-builds.sh" 16c23e5 e930860 "${1:-/tmp/pirqa-uplift-gcd}"
