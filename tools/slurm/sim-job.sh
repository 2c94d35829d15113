#!/usr/bin/env bash
# The simulation job of a scene's chain on Slurm (Makefile.scenes SCHEDULER=slurm;
# docs/cluster.md): makes OUTDIR/run.h5 with `make -f Makefile.scenes MAKE_ARGS...`,
# and when Slurm signals the coming time limit (sbatch --signal=B:TERM@SECONDS, to
# this batch shell), passes SIGTERM on to make and bw-sim, waits until bw-sim has
# finished its frame and written its checkpoint, and requeues the job, which then
# resumes from the checkpoint. Slurm itself requeues a job on a node failure
# (--requeue), not on a time limit: the job requeues itself.
#
#   sbatch --requeue --signal=B:TERM@120 ... tools/slurm/sim-job.sh OUTDIR MAKE_ARGS...
set -uo pipefail
out=$1
shift
echo "sim-job: job ${SLURM_JOB_ID:-?} run $((${SLURM_RESTART_COUNT:-0} + 1)) on $(hostname) at $(date -u +%FT%TZ)"
stopped=0
# make and bw-sim in a process group of their own, so that one kill reaches both.
setsid make -f Makefile.scenes "$@" &
pid=$!
# Passed on once: bw-sim ends at once on a second SIGTERM, without its checkpoint, and
# Slurm's early signal can meet a preemption or an scancel --signal.
on_term() {
  ((stopped)) && return
  stopped=1
  echo "sim-job: SIGTERM at $(date -u +%FT%TZ): bw-sim finishes its frame and writes a checkpoint"
  kill -TERM -- -$pid 2>/dev/null
}
trap on_term TERM
wait $pid; rc=$?
while kill -0 $pid 2>/dev/null; do wait $pid; rc=$?; done
# make may be gone before bw-sim: wait for the whole group.
while kill -0 -- -$pid 2>/dev/null; do sleep 0.2; done
if [[ $stopped -eq 1 && -e $out/checkpoint.h5 ]]; then
  echo "sim-job: requeued; the next run resumes from $out/checkpoint.h5"
  scontrol requeue "$SLURM_JOB_ID"
  sleep 30  # Slurm ends this run now
  exit 0
fi
exit $rc
