#!/usr/bin/env bash
# Reproduces the uplift check's times before and after the p-adic solves (docs/rocking-walls.md,
# "The vertex and multipliers by p-adic lifting"): the build before (dbc8efd) and the build
# with them (a5474e2) on the eight 105-block cases, side by side (uplift-two-builds.sh). About
# 20 minutes with the two builds.
#
#   bash docs/experiments/uplift-padic.sh [WORKDIR]
set -euo pipefail
exec bash "$(dirname "$0")/uplift-two-builds.sh" dbc8efd a5474e2 "${1:-/tmp/pirqa-uplift-padic}"
