#!/usr/bin/env bash
# Runs bw-sim into OUTDIR, or goes on from OUTDIR/checkpoint.h5 when a stopped run
# left one (Makefile.scenes, the run of a scene; docs/cluster.md):
#
#   tools/slurm/sim-or-resume.sh BW_SIM OUTDIR DEVICE SCENE [bw-sim options...]
#
# A checkpoint that does not fit the run (the scene or its files changed since) is
# refused by bw-sim (exit 2); the run then starts afresh. Exits with bw-sim's status:
# 0, 1, 2, or 128 + the signal that stopped it (with a new checkpoint).
set -uo pipefail
sim=$1 out=$2 device=$3
shift 3
# The signal reaches bw-sim, which finishes its frame; this shell waits for it.
trap 'true' TERM INT
if [[ -e $out/checkpoint.h5 ]]; then
  "$sim" --resume "$out" --device "$device" &
  wait $! ; rc=$?
  while [[ $rc -gt 128 ]] && kill -0 $! 2>/dev/null; do wait $!; rc=$?; done
  [[ $rc -ne 2 ]] && exit $rc
  echo "sim-or-resume: $out/checkpoint.h5 does not fit this run (above); starting afresh" >&2
  rm -f "$out/checkpoint.h5"
fi
"$sim" "$@" -o "$out" --device "$device" &
pid=$!
wait $pid; rc=$?
while [[ $rc -gt 128 ]] && kill -0 $pid 2>/dev/null; do wait $pid; rc=$?; done
exit $rc
