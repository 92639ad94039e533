#!/usr/bin/env bash
# One shard of a capstan sweep per Slurm array task; merge the parts afterwards.
#
#   jid=$(sbatch --parsable --array=1-8 scripts/slurm_sweep.sh \
#           --param body.poisson --from 0.1 --to 0.45 --steps 64 --set grid.n2=500)
#   sbatch --dependency=afterok:$jid --wrap "capstan merge sweep-out/parts --out sweep-out"
#
# Task I of an array of N (contiguous ids, any first id: --array=0-7 works too) runs
# `capstan sweep ... --shard I/N`: the 0-based points k with k % N == I - 1, written to
# $OUT/parts/shard-I-of-N.json (OUT must be on a file system every node sees).
#
# Environment: CAPSTAN (the binary; default `capstan` on PATH), OUT (default sweep-out),
# SHARDS (default SLURM_ARRAY_TASK_COUNT), SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_MIN (set
# by Slurm; set them by hand to run one task without Slurm, as tests/shard_scripts.rs does).
#SBATCH --job-name=capstan-sweep
#SBATCH --cpus-per-task=2
#SBATCH --time=01:00:00
set -euo pipefail

: "${SLURM_ARRAY_TASK_ID:?run as a Slurm array job (sbatch --array=1-N) or set SLURM_ARRAY_TASK_ID}"
first=${SLURM_ARRAY_TASK_MIN:-1}
count=${SHARDS:-${SLURM_ARRAY_TASK_COUNT:?set SHARDS or SLURM_ARRAY_TASK_COUNT}}
index=$((SLURM_ARRAY_TASK_ID - first + 1))
out=${OUT:-sweep-out}
# The points of a shard run in parallel on the task's cores (rayon), one factorisation each.
export RAYON_NUM_THREADS=${RAYON_NUM_THREADS:-${SLURM_CPUS_PER_TASK:-1}}

exec "${CAPSTAN:-capstan}" sweep "$@" --shard "$index/$count" --out "$out/parts"
