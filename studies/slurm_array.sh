#!/usr/bin/env bash
# Run one beamid study on a Slurm cluster as a job array: every array task runs one shard of the study's units
# into its own folder, and a final job merges the shards into exactly the tables a single run gives.
#
#   sbatch --array=1-16 studies/slurm_array.sh studies/paper.toml 16         # 16 shards
#   sbatch --dependency=afterok:<array job id> --wrap \
#       "build/beamid merge studies/paper.toml --shards $(ls -d results/paper-shard-* | paste -sd,)"
#
# A shard that dies can be resubmitted alone, with the same shard count: sbatch --array=7 studies/slurm_array.sh
# studies/paper.toml 16. It resumes from its store and redoes only the units it had not finished; then submit the
# merge again (the first one's afterok can no longer be met). The count is an argument because a resubmitted task's
# array has one task (SLURM_ARRAY_TASK_COUNT would say 1); it defaults to the array's size for a full submission.
# All shards must use the same beamid build (records from another build are recomputed). Build first on a login
# node: make build. `make test-slurm` runs all of this on a single-node Slurm (tests/slurm/slurm_test.sh).
#SBATCH --job-name=beamid-study
#SBATCH --cpus-per-task=4
#SBATCH --time=02:00:00
#SBATCH --output=beamid-%A_%a.log
set -euo pipefail
study_file=${1:?usage: sbatch --array=1-N studies/slurm_array.sh STUDY.toml [N]}
name=$(basename "$study_file" .toml)
index=${SLURM_ARRAY_TASK_ID:?run me with sbatch --array=1-N}
shards=${2:-${SLURM_ARRAY_TASK_COUNT:?run me with sbatch --array=1-N}}
# Task ids must be 1..N (the shard index K of --shard K/N); beamid refuses any other.
exec build/beamid study "$study_file" --jobs "${SLURM_CPUS_PER_TASK:-1}" \
    --shard "$index/$shards" --output "results/$name-shard-$index"
