#!/usr/bin/env bash
# SPHERIC Test 2 (docs/validation.md, "Impact pressure") with the bundled tools
# (tools/gpu-bundle.sh) on one OpenCL device, for a machine with only a GPU driver:
# the scene at each spacing, diffusion coefficient, kernel vector width and draw
# (fluid.seed, docs/scene.md "Draws") asked for, each run its face sensors' report
# against the experiment (rise, peak, mean and noise over 0.45-0.55 s, the peak of
# the 20 ms mean; tests/study/spheric-report.sh) and, where a spacing and coefficient
# ran at two widths or seeds or more, the spread over those draws
# (tests/study/spheric-spread.sh). The driver is set up as tools/gpu-check.sh does it (tools/gpu-driver.sh). Runs go in
# the order given, cheapest first is best; each has what is left of --budget, and
# one stopped at its limit (SIGTERM: bw-sim closes its files) is reported as far as
# it went. Run from the repository's root (the report scripts and the experiment's
# data are the working tree's).
#
#   tools/gpu-spheric.sh --bundle out/gpu-bundle.tar.gz --out out/gpu-spheric \
#       --spacings 0.02,0.01 --diffusion 0.1,0.3 --widths device,2
#   tools/gpu-spheric.sh --bundle out/gpu-bundle.tar.gz --out OUT --spacings 0.01 --seeds 0,1,2,3
#   tools/gpu-spheric.sh --bundle out/gpu-bundle.tar.gz --out OUT --spacings 0.005 --budget 420
#   make -f Makefile.scenes gpu-spheric GPU_SPHERIC_SPACINGS=0.02,0.01
#
# OUTDIR: runs.csv (one row per run: spacing, diffusion, width, exit status, steps,
# simulated and wall seconds, fluid particles, device, seed), summary.md (every
# report's table), gpu-spheric.log, and SPACING/dDELTA-wWIDTH/ per run (-sSEED after
# it for a draw) (sensors.csv and the
# report spheric2.{csv,md}, spheric2.png where gnuplot is installed) and
# SPACING/dDELTA/spheric2-spread.{csv,md} (DELTA "scene" without --diffusion). Exit
# status 0 when every run reached --end, 1 when one failed or stopped short, 2 on
# bad usage.
set -euo pipefail

usage() {
  sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'
  cat <<'EOF'
Options:
  --bundle DIR      the bundle (tools/gpu-bundle.sh), or its .tar.gz (--tar)
  --out DIR         where the reports go (created)
  --spacings LIST   particle spacings in m, comma-separated (default 0.02)
  --diffusion LIST  fluid.diffusion values (default: the scene's, 0.1)
  --widths LIST     kernel vector widths: device (the device's own) or 1, 2, 4, 8, 16 (default device)
  --seeds LIST      draws at each width: fluid.seed values, 0 the lattice as it is (default 0)
  --end S           simulated seconds of each run (default 0.56: past the window 0.45-0.55 s)
  --frames HZ       frames a second written (default 10; the sensors are sampled apart from them). A run
                    stopped at its limit finishes its frame (killed 90 s after): at millions of
                    particles take 20 or more
  --device gpu|cpu  the OpenCL device type (default gpu)
  --budget S        wall-clock seconds for all the runs (default 540)
  --work DIR        keep the runs' files here (default: a temporary folder, removed)
EOF
}
die() { echo "gpu-spheric: $1" >&2; exit "${2:-1}"; }
number() { [[ $2 =~ ^[0-9]*\.?[0-9]+$ ]] || die "$1: '$2' is not a positive number" 2; }

bundle="" out="" spacings=0.02 diffusions="" widths=device seeds=0 end=0.56 frames=10 device=gpu budget=540 work=""
while [[ $# -gt 0 ]]; do
  case $1 in
    -h|--help) usage; exit 0 ;;
    --bundle|--out|--spacings|--diffusion|--widths|--seeds|--end|--frames|--device|--budget|--work)
      [[ $# -ge 2 && -n $2 ]] || die "$1 needs a value (see --help)" 2
      case $1 in
        --bundle) bundle=$2 ;; --out) out=$2 ;; --spacings) spacings=$2 ;; --diffusion) diffusions=$2 ;;
        --widths) widths=$2 ;; --seeds) seeds=$2 ;; --end) end=$2 ;; --frames) frames=$2 ;; --device) device=$2 ;;
        --budget) budget=$2 ;; --work) work=$2 ;;
      esac
      shift 2 ;;
    *) die "unknown argument '$1' (see --help)" 2 ;;
  esac
done
[[ -n $bundle ]] || die "no bundle given (--bundle DIR, made by tools/gpu-bundle.sh)" 2
[[ -n $out ]] || die "no output folder given (--out DIR)" 2
[[ $device == gpu || $device == cpu ]] || die "--device: '$device' is not gpu or cpu" 2
[[ $budget =~ ^[0-9]+$ ]] || die "--budget: '$budget' is not a whole number of seconds" 2
number --end "$end"
number --frames "$frames"
IFS=, read -r -a spacing_list <<< "$spacings"
IFS=, read -r -a width_list <<< "$widths"
IFS=, read -r -a seed_list <<< "$seeds"
diffusion_list=(scene)
[[ -z $diffusions ]] || IFS=, read -r -a diffusion_list <<< "$diffusions"
for s in "${spacing_list[@]}"; do number --spacings "$s"; done
for d in "${diffusion_list[@]}"; do [[ $d == scene ]] || number --diffusion "$d"; done
for w in "${width_list[@]}"; do
  [[ $w =~ ^(device|1|2|4|8|16)$ ]] || die "--widths: '$w' is not device, 1, 2, 4, 8 or 16" 2
done
for n in "${seed_list[@]}"; do
  [[ $n =~ ^[0-9]+$ ]] || die "--seeds: '$n' is not a whole number, 0 or more" 2
done
root=$(cd "$(dirname "$0")/.." && pwd)
reference=$root/examples/data/spheric-test2-pressure.txt
[[ -f $reference ]] || die "$reference: missing (run from a checkout of the repository)" 2
if [[ -f $bundle && $bundle == *.tar.gz ]]; then
  tar -tzf "$bundle" >/dev/null 2>&1 || die "$bundle: not a gzip tar file (tools/gpu-bundle.sh --tar makes one)" 2
elif [[ ! -x $bundle/bin/bw-sim ]]; then
  die "$bundle: not a bundle (no bin/bw-sim; tools/gpu-bundle.sh makes one)" 2
fi

mkdir -p "$out"
out=$(cd "$out" && pwd)
if [[ -z $work ]]; then
  work=$(mktemp -d "${TMPDIR:-/tmp}/gpu-spheric.XXXXXX")
  trap 'rm -rf "$work"' EXIT
else
  mkdir -p "$work"
  work=$(cd "$work" && pwd)
fi
if [[ -f $bundle ]]; then
  mkdir -p "$work/bundle"
  tar -xzf "$bundle" -C "$work/bundle"
  bundle=$(dirname "$(dirname "$(ls -d "$work"/bundle/*/bin/bw-sim | head -1)")")
fi
bundle=$(cd "$bundle" && pwd)
B=$bundle/bin
log=$out/gpu-spheric.log
: > "$log"
start=$SECONDS
say() { echo "gpu-spheric: $*" | tee -a "$log" >&2; }
left() { echo $(( budget - (SECONDS - start) )); }
key() { awk -F= -v k="$1" '$1 == k { sub(/^[^=]*=/, ""); print; exit }' "$2"; }

# shellcheck source=tools/gpu-driver.sh
source "$root/tools/gpu-driver.sh"
say "$(date -u +%Y-%m-%dT%H:%M:%SZ) on ${HOSTNAME:-?}, device $device, budget $budget s"
if [[ $device == gpu ]]; then
  gpu_driver_setup "$work" > "$work/driver.txt"  # not in a subshell: it exports
  while IFS= read -r line; do say "$line"; done < "$work/driver.txt"
  if command -v nvidia-smi >/dev/null; then
    say "nvidia-smi: $(nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader 2>&1 | head -1)"
  fi
fi
gpu_cxx_runtime "$bundle" > "$work/runtime.txt" || die "$B/bw-info does not start on this machine (ldd $B/bw-info says why)"
say "$(cat "$work/runtime.txt")"
"$B/bw-sim" --device list 2>&1 | tee -a "$log" >&2

# The tank and the box at each spacing, sampled here (at 0.005 m the tank alone is
# 45 MB: cheaper to make than to carry).
for s in "${spacing_list[@]}"; do
  mkdir -p "$work/$s"
  for m in tank box; do
    "$B/bw-sample" "$root/examples/meshes/spheric_$m.obj" -o "$work/$s/$m.h5" --spacing "$s" >> "$log" 2>&1 ||
      die "bw-sample of spheric_$m.obj at $s m failed ($log)"
  done
done

echo "spacing,diffusion,width,exit,steps,simulated_s,wall_s,fluid,device,seed" > "$out/runs.csv"
: > "$out/summary.md"
failed=0
for s in "${spacing_list[@]}"; do
  for d in "${diffusion_list[@]}"; do
    reports=()
    for w in "${width_list[@]}"; do
      for n in "${seed_list[@]}"; do
        name=d$d-w$w
        (( n == 0 )) || name+=-s$n
        dir=$out/$s/$name run=$work/$s/$name
        limit=$(( $(left) - 10 ))
        if (( limit < 20 )); then say "$s m, $name: not run, the budget is spent"; failed=1; continue; fi
        mkdir -p "$dir" "$run"
        sets=(--set "spacing=$s" --set "solid[0].particles=$work/$s/tank.h5" --set "solid[1].particles=$work/$s/box.h5"
              --set "time.end=$end" --set "time.frame_rate=$frames")
        [[ $d == scene ]] || sets+=(--set "fluid.diffusion=$d")
        (( n == 0 )) || sets+=(--set "fluid.seed=$n")
        rc=0 t0=$SECONDS
        # The width in bw-sim's environment only (libcore/compute/kernels.cpp).
        width_env=(BW_KERNEL_VECTOR_WIDTH="$w")
        [[ $w != device ]] || width_env=(-u BW_KERNEL_VECTOR_WIDTH)
        env "${width_env[@]}" timeout -s TERM -k 90 "$limit" "$B/bw-sim" "$root/examples/spheric2.toml" \
          -o "$run" --device "$device" "${sets[@]}" > "$dir/bw-sim.log" 2>&1 || rc=$?
        if [[ ! -s $run/run.h5 ]] || ! "$B/bw-measure" sensors "$run/run.h5" > "$dir/sensors.csv" 2>> "$log"; then
          say "$s m, $name: bw-sim exit $rc, no sensors ($(tail -1 "$dir/bw-sim.log" | cut -c1-200))"
          echo "$s,$d,$w,$rc,,,$(( SECONDS - t0 )),,,$n" >> "$out/runs.csv"
          failed=1
          continue
        fi
        "$B/gpu-tool" rate "$run/run.h5" --last 1 > "$run/rate.txt" 2>> "$log" || true
        echo "$s,$d,$w,$rc,$(key steps "$run/rate.txt"),$(key simulated "$run/rate.txt"),$(( SECONDS - t0 )),$(key fluid "$run/rate.txt"),\"$(key device "$run/rate.txt")\",$n" >> "$out/runs.csv"
        (( rc == 0 )) || { failed=1; say "$s m, $name: stopped (exit $rc, 124: the time limit of $limit s); reported as far as it went"; }
        "$root/tests/study/spheric-report.sh" "$dir/sensors.csv" "$reference" "$dir/spheric2" "$s" > /dev/null 2>> "$log" ||
          { say "$s m, $name: spheric-report.sh failed ($log)"; failed=1; continue; }
        reports+=("$dir/spheric2.csv")
        say "$s m, $name: exit $rc, $(key steps "$run/rate.txt") steps in $(( SECONDS - t0 )) s"
        { echo "### $s m, diffusion $d, width $w, seed $n (exit $rc, $(key steps "$run/rate.txt") steps, $(( SECONDS - t0 )) s)"
          echo; cat "$dir/spheric2.md"; echo; } >> "$out/summary.md"
      done
    done
    if (( ${#reports[@]} >= 2 )); then
      mkdir -p "$out/$s/d$d"
      "$root/tests/study/spheric-spread.sh" "$out/$s/d$d/spheric2-spread" "${reports[@]}" > /dev/null 2>> "$log" || failed=1
      { echo "### $s m, diffusion $d: over ${#reports[@]} draws (widths $widths, seeds $seeds), mean ± sd (least to largest)"
        echo; cat "$out/$s/d$d/spheric2-spread.md"; echo; } >> "$out/summary.md"
    fi
  done
done
say "done in $(( SECONDS - start )) s"
cat "$out/runs.csv" >&2
exit $failed
