#!/usr/bin/env bash
# Run one beamid study on a Slurm cluster as a job array: every array task runs one shard of the study's units
# into its own folder, and a final job merges the shards into exactly the tables a single run gives.
#
#   sbatch --array=1-16 studies/slurm_array.sh studies/paper.toml            # 16 shards
#   sbatch --dependency=afterok:<array job id> --wrap \
#       "build/beamid merge studies/paper.toml --shards $(ls -d results/paper-shard-* | paste -sd,)"
#
# A shard that dies can be resubmitted alone (sbatch --array=7 ...): it resumes from its store and redoes only the
# units it had not finished. All shards must use the same beamid build (records from another build are recomputed).
# Build first on a login node: make build.
#SBATCH --job-name=beamid-study
#SBATCH --cpus-per-task=4
#SBATCH --time=02:00:00
#SBATCH --output=beamid-%A_%a.log
set -euo pipefail
study_file=${1:?usage: sbatch --array=1-N studies/slurm_array.sh STUDY.toml}
name=$(basename "$study_file" .toml)
shards=${SLURM_ARRAY_TASK_COUNT:?run me with sbatch --array=1-N}
index=${SLURM_ARRAY_TASK_ID:?run me with sbatch --array=1-N}
# Task ids must be 1..N (the shard index K of --shard K/N).
exec build/beamid study "$study_file" --jobs "${SLURM_CPUS_PER_TASK:-1}" \
    --shard "$index/$shards" --output "results/$name-shard-$index"
