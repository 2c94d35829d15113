#!/usr/bin/env bash
# SCHEDULER=slurm for real: starts a single-node Slurm here (local-slurm.sh), runs a
# reduced dam break (SPACING 0.005, 0.5 s, small images) through
# `make -f Makefile.scenes dambreak SCHEDULER=slurm`, stops the simulation job's first
# run once it has written its first checkpoint with the signal that sbatch
# --signal=B:TERM@N has Slurm send before a time limit (scancel --batch
# --signal=TERM, to the batch shell), so that the job requeues itself and resumes
# from its checkpoint, and compares every file with the same scene run here without
# Slurm: the particle files, frames, images and video byte for byte, the run file
# but for its wall times. Exits 77 (skipped, ctest SKIP_RETURN_CODE) only when Slurm
# cannot start.
#
#   tests/slurm/slurm_scene_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
src=$(cd "$1" && pwd)
build=$(cd "$2" && pwd)
tmp=$(mktemp -d /tmp/bw-slurm-test.XXXXXX)
cleanup() {
  "$src/tests/slurm/local-slurm.sh" stop "$tmp/cluster" >/dev/null 2>&1 || true
  rm -rf "$tmp"
}
trap cleanup EXIT
say() { echo "slurm_scene_test: $*"; }
logs() {  # what went on, when something failed
  tail -n 20 "$tmp"/out/slurm/dambreak/*.out "$tmp/cluster/log/slurmctld.log" 2>/dev/null || true
}

rc=0
env=$("$src/tests/slurm/local-slurm.sh" start "$tmp/cluster") || rc=$?
if [[ $rc -eq 77 ]]; then say "SKIPPED: Slurm cannot start on this machine (reason above)"; exit 77; fi
[[ $rc -eq 0 ]] || { say "local-slurm.sh start failed ($rc)"; exit 1; }
eval "$env"
say "Slurm up ($SLURM_CONF)"

vars=(NO_BUILD=1 BUILD="$build" SPACING=0.005 END=0.5 WIDTH=64 HEIGHT=36 RENDER_CHUNK=8 DEVICE=cpu)
dir=scenes/dambreak/0.005-end0.5

start=$SECONDS
# Both runs write into the same OUT (the run file records its absolute paths), the
# local one moved aside after it.
make -s -C "$src" -f Makefile.scenes dambreak "${vars[@]}" OUT="$tmp/out" >"$tmp/local.log" 2>&1 \
  || { cat "$tmp/local.log"; say "the local run failed"; exit 1; }
mv "$tmp/out" "$tmp/local"
say "local run: $((SECONDS - start)) s"

start=$SECONDS
make -s -C "$src" -f Makefile.scenes dambreak "${vars[@]}" OUT="$tmp/out" SCHEDULER=slurm SLURM_SIM_TIME=10 \
  SLURM_SIM_SIGNAL=59 SLURM_CHECKPOINT_EVERY=4 SLURM_TIME=10 SLURM_ARRAY_WIDTH=2 \
  SLURM_SBATCH="--cpus-per-task=1" | tee "$tmp/submit.log"
jobs=$tmp/out/slurm/dambreak/jobs
[[ -f $jobs ]] || { say "no job ids ($jobs)"; exit 1; }
sim=$(awk '$1 == "sim" { print $2 }' "$jobs")
video=$(awk '$1 == "video" { print $2 }' "$jobs")
state() { scontrol show job "$1" 2>/dev/null | grep -o 'JobState=[A-Z_]*' | cut -d= -f2; }
# Wait for the video job; a requeued simulation waits Slurm's requeue delay for its
# next start: the credential lifetime, 10 s in local-slurm.sh's slurm.conf (120 s by
# default). Starting it sooner (scontrol update StartTime=now) races the revocation of
# its last run's credential, and slurmd kills the new run ("Job credential revoked").
# The test sends the signal itself: Slurm checks time limits every 30 s, so a job
# with a limit near enough to be signalled during a 15 s simulation can also be
# signalled as it starts, before bw-sim has anything to checkpoint, and a limit too
# far for that lets a fast machine finish first. The job's limit is 10 minutes.
signalled=
checkpoint=$tmp/out/$dir/checkpoint.h5
while :; do
  s=$(state "$video")
  case $s in
    COMPLETED) break ;;
    FAILED|CANCELLED|TIMEOUT|NODE_FAIL|OUT_OF_MEMORY|"")
      say "video job $video: ${s:-gone}"; logs; exit 1 ;;
  esac
  if [[ -z $signalled && -e $checkpoint && $(state "$sim") == RUNNING ]] \
    && scontrol show job "$sim" | grep -q 'Restarts=0'; then
    scancel --batch --signal=TERM "$sim" && signalled=1 && say "signalled the first run after its first checkpoint"
  fi
  if [[ $(state "$sim") =~ ^(FAILED|CANCELLED|TIMEOUT)$ ]] || ((SECONDS - start > 300)); then
    say "simulation job $sim: $(state "$sim") after $((SECONDS - start)) s"; logs; exit 1
  fi
  if [[ -z $signalled ]]; then sleep 0.2; else sleep 1; fi
done
say "Slurm run: $((SECONDS - start)) s"
cat "$tmp/out/slurm/dambreak/sim.out"

fail=0
restarts=$(scontrol show job "$sim" | grep -o 'Restarts=[0-9]*' | cut -d= -f2)
if [[ ${restarts:-0} -lt 1 ]]; then say "FAIL: the simulation job was never stopped and requeued"; fail=1; fi
if ! grep -q "resumed after frame" "$tmp/out/slurm/dambreak/sim.out"; then
  say "FAIL: the simulation job did not resume from a checkpoint"; fail=1
fi
say "simulation job $sim: requeued $restarts times"

a=$tmp/local/$dir b=$tmp/out/$dir
[[ ! -e $b/checkpoint.h5 ]] || { say "FAIL: a checkpoint was left in $b"; fail=1; }
n=0
while IFS= read -r f; do
  if ! cmp -s "$a/$f" "$b/$f"; then say "FAIL: $f differs"; fail=1; fi
  n=$((n + 1))
done < <(cd "$a" && find . -type f ! -name run.h5 ! -name '.frames-*' | sort)
if ! diff <(cd "$a" && find . -type f | sort) <(cd "$b" && find . -type f | sort) >/dev/null; then
  say "FAIL: the files differ:"; diff <(cd "$a" && find . -type f | sort) <(cd "$b" && find . -type f | sort) || true
  fail=1
fi
if ! h5diff --exclude-path /frames/wall_time --exclude-path /summary/wall_time "$a/run.h5" "$b/run.h5"; then
  say "FAIL: run.h5 differs beyond its wall times"; fail=1
fi
say "compared $n files and run.h5"
[[ $fail -eq 0 ]] && say "OK"
exit $fail
