#!/usr/bin/env bash
# A capstan sweep in SHARDS parts run by GNU parallel (JOBS at a time), then merged.
#
#   SHARDS=8 JOBS=2 scripts/parallel_sweep.sh --param body.poisson --from 0.1 --to 0.45 --steps 64
#
# Across machines, pass parallel's own options, e.g.
#   PARALLEL_ARGS="--sshlogin 4/node1,4/node2 --workdir ." (OUT must be on a shared file system).
# Without GNU parallel (or with NO_PARALLEL=1) the same shards run in a plain shell loop.
#
# Environment: CAPSTAN (the binary; default `capstan` on PATH), OUT (default sweep-out; the
# parts go to $OUT/parts, the merged sweep.json and sweep.csv to $OUT), SHARDS (default 4),
# JOBS (default SHARDS).
set -euo pipefail

shards=${SHARDS:-4}
jobs=${JOBS:-$shards}
out=${OUT:-sweep-out}
capstan=${CAPSTAN:-capstan}
mkdir -p "$out/parts"

if [ -z "${NO_PARALLEL:-}" ] && command -v parallel >/dev/null 2>&1; then
  # -q quotes every argument, so values with spaces or '*' (--set 'obstacle.u=2*sin(t)') pass
  # through intact; --halt stops the other shards when one fails.
  # shellcheck disable=SC2086 # PARALLEL_ARGS is a list of options
  seq 1 "$shards" | parallel --will-cite --halt now,fail=1 -j "$jobs" ${PARALLEL_ARGS:-} \
    -q "$capstan" sweep "$@" --shard "{}/$shards" --out "$out/parts"
else
  echo "parallel_sweep.sh: running the $shards shards in a shell loop (no GNU parallel)" >&2
  failed=$(mktemp)
  trap 'rm -f "$failed"' EXIT
  for i in $(seq 1 "$shards"); do
    { "$capstan" sweep "$@" --shard "$i/$shards" --out "$out/parts" || echo "$i" >>"$failed"; } &
    while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n || true; done
  done
  wait
  if [ -s "$failed" ]; then
    echo "parallel_sweep.sh: shards failed: $(tr '\n' ' ' <"$failed")" >&2
    exit 1
  fi
fi

"$capstan" merge "$out/parts" --out "$out"
