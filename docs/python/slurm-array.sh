#!/usr/bin/env bash
# A pirqa sweep as a Slurm job array: each task runs one part of the sweep into OUT/parts/I-of-N.
#
#   sbatch --array=0-31 docs/python/slurm-array.sh walls/studies/fragility.ron out/fragility
#   # when every task is done (or chained: sbatch --dependency=afterok:JOBID ...):
#   pirqa sweep merge out/fragility
#
# The part comes from Slurm's SLURM_ARRAY_TASK_* variables (--shard auto); a task that is
# requeued or resubmitted continues its part where it stopped (--resume). PIRQA names the
# binary (default: pirqa on the PATH). The sweep file and the walls and records it names must be
# readable by every node at the same path.
#SBATCH --job-name=pirqa-sweep
#SBATCH --cpus-per-task=2
#SBATCH --time=01:00:00
#SBATCH --output=pirqa-sweep-%A_%a.log
set -euo pipefail
if [ $# -ne 2 ]; then
    echo "usage: sbatch --array=0-N docs/python/slurm-array.sh SWEEP.ron OUT_DIR" >&2
    exit 2
fi
"${PIRQA:-pirqa}" sweep "$1" --shard auto --out "$2" --resume --threads "${SLURM_CPUS_PER_TASK:-1}"
