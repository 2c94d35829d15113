#!/usr/bin/env bash
# The GPU check: runs the bundled tools (tools/gpu-bundle.sh) on one OpenCL device
# and the EGL device the machine offers, and writes every figure and a few PNGs to
# one folder. On a GPU machine with only a driver installed, it points the bundled
# ICD loader at the driver's libnvidia-opencl.so.1 through an ICD file of its own
# and glvnd's EGL at the driver's EGL vendor file; on a CPU it takes PoCL and Mesa
# as installed. The steps, the same on both, in this order:
#   devices     the OpenCL devices, the EGL devices and the OpenGL context made
#   agreement   the bundle's CPU reference of a dam break run again on the device:
#               particles matched by id, and one frame drawn by the device's renderer,
#               against the stated tolerances
#   bench-sim   the dam-break benchmark at 30 k, 120 k, 1 M and 4 M fluid particles
#   bench-render  ms per 1280 x 720 frame at 120 k and 1 M particles
#   wall        scene 1 at the paper's size (spacing 0.02, 32 k) until its emitter stops
#   render      frames of the wall run drawn at 1280 x 720
#   valley      scene 3 at the paper's size (spacing 0.0125, 650 k) until its emitter
#               stops (2.15 s) or the budget ends; steps per second over its last frames
# Every step has a time limit within --budget (450 s), so that the whole check ends
# within 8 minutes; a run stopped at its limit is measured as far as it went.
# --quick runs every step at small sizes and short times (a minute on 2 cores).
#
#   tools/gpu-check.sh --bundle out/gpu-bundle --out out/gpu-check            # the GPU
#   tools/gpu-check.sh --bundle out/gpu-bundle.tar.gz --out out/gpu-check     # from the tarball
#   tools/gpu-check.sh --bundle out/gpu-bundle --out /tmp/check --quick --device cpu
#   make -f Makefile.scenes gpu-check GPU_DEVICE=cpu GPU_QUICK=1
#
# OUTDIR gets at most 8 files: summary.txt, figures.csv, figures.json, gpu-check.log
# (every command and its output), wall.png, dambreak-cpu.png, dambreak-device.png,
# dambreak-diff.png. Exit status: 0 when every step ran and the agreement holds, 3
# when the frames or images disagree beyond the tolerances, 1 when a step failed
# (the others still run), 2 on bad usage. Targets missed are figures, not failures.
set -euo pipefail

usage() {
  sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'
  cat <<'EOF'
Options:
  --bundle DIR      the bundle (tools/gpu-bundle.sh), or its .tar.gz (--tar)
  --out DIR         where the figures and PNGs go (created)
  --device gpu|cpu  the OpenCL device type of every simulation (default gpu)
  --quick           small sizes and short runs
  --work DIR        keep the runs' files here (default: a temporary folder, removed)
  --budget S        wall-clock seconds for all the steps (default 450; quick 240)
EOF
}
die() { echo "gpu-check: $1" >&2; exit "${2:-1}"; }

bundle="" out="" device=gpu quick=0 work="" budget=""
while [[ $# -gt 0 ]]; do
  case $1 in
    -h|--help) usage; exit 0 ;;
    --bundle|--out|--device|--work|--budget)
      [[ $# -ge 2 && -n $2 ]] || die "$1 needs a value (see --help)" 2
      case $1 in
        --bundle) bundle=$2 ;; --out) out=$2 ;; --device) device=$2 ;; --work) work=$2 ;; --budget) budget=$2 ;;
      esac
      shift 2 ;;
    --quick) quick=1; shift ;;
    *) die "unknown argument '$1' (see --help)" 2 ;;
  esac
done
[[ -n $bundle ]] || die "no bundle given (--bundle DIR, made by tools/gpu-bundle.sh)" 2
[[ -n $out ]] || die "no output folder given (--out DIR)" 2
[[ $device == gpu || $device == cpu ]] || die "--device: '$device' is not gpu or cpu" 2
[[ -z $budget || $budget =~ ^[0-9]+$ ]] || die "--budget: '$budget' is not a whole number of seconds" 2
if [[ -f $bundle && $bundle == *.tar.gz ]]; then
  tar -tzf "$bundle" >/dev/null 2>&1 || die "$bundle: not a gzip tar file (tools/gpu-bundle.sh --tar makes one)" 2
elif [[ ! -x $bundle/bin/bw-sim || ! -d $bundle/share/reference ]]; then
  die "$bundle: not a bundle (no bin/bw-sim or share/reference; tools/gpu-bundle.sh makes one)" 2
fi

# ---- sizes: the paper's, or small ones for --quick
if (( quick )); then
  sim_sizes=8000,30000 render_counts="30000" wall_spacing=0.05 wall_end=0.1 valley_spacing=0.1 valley_end=0.1
  render_frames=2 budget=${budget:-240}
else
  sim_sizes=30000,120000,1000000,4000000 render_counts="120000 1000000"
  wall_spacing=0.02 wall_end=0.75 valley_spacing=0.0125 valley_end=2.15 render_frames=3 budget=${budget:-450}
fi
# Tolerances of the agreement (docs/performance.md, "On a GPU" says how they were set).
# The dam break is chaotic particle by particle (a difference of rounding grows some
# 100-fold in 0.05 s), so particles are matched by id only at 0.05 s, in spacings;
# at 0.3 s the flow is compared as the share of the particles found in other cells
# of 4 spacings. The drawn frame: the mean difference in 0-255 levels per channel,
# and the share of the pixels off by more than 32 levels.
tol_id_until=0.05 tol_rms=0.05 tol_p99=0.2 tol_cell=4 tol_moved=0.08 tol_mean=4 tol_share=0.05

mkdir -p "$out"
out=$(cd "$out" && pwd)
rm -f "$out"/{summary.txt,figures.csv,figures.json,gpu-check.log,wall.png,dambreak-cpu.png,dambreak-device.png,dambreak-diff.png}
if [[ -z $work ]]; then
  work=$(mktemp -d "${TMPDIR:-/tmp}/gpu-check.XXXXXX")
  trap 'rm -rf "$work"' EXIT
else
  mkdir -p "$work"
  work=$(cd "$work" && pwd)
fi
if [[ -f $bundle ]]; then  # a tarball: unpacked into the work folder
  mkdir -p "$work/bundle"
  tar -xzf "$bundle" -C "$work/bundle"
  bundle=$(dirname "$(ls -d "$work"/bundle/*/bin/bw-sim | head -1)")
  bundle=$(dirname "$bundle")
fi
bundle=$(cd "$bundle" && pwd)
B=$bundle/bin EX=$bundle/share/examples REF=$bundle/share/reference
log=$out/gpu-check.log
csv=$out/figures.csv
echo "step,figure,value,unit,target,paper,verdict" > "$csv"
failures=() disagreements=()
start=$SECONDS

say() { echo "gpu-check: $*" | tee -a "$log" >&2; }
# fig STEP FIGURE VALUE UNIT [TARGET [PAPER [VERDICT]]]
fig() { echo "$1,$2,$3,$4,${5:-},${6:-},${7:-}" >> "$csv"; }
left() { echo $(( budget - (SECONDS - start) )); }
# run_step NAME SECONDS COMMAND...: runs it with a time limit (no more than what is
# left of the budget), its output into the log and into WORK/NAME.txt; returns its
# exit status (124: out of time).
run_step() {
  local name=$1 limit=$2; shift 2
  (( limit <= $(left) )) || limit=$(left)
  (( limit > 0 )) || { say "$name: no time left of the --budget $budget s"; return 124; }
  echo "== $name (limit ${limit} s): $*" >> "$log"
  local t0=$SECONDS rc=0
  timeout --kill-after=10 "$limit" "$@" > "$work/$name.txt" 2>&1 || rc=$?
  cat "$work/$name.txt" >> "$log"
  echo "== $name: exit $rc after $(( SECONDS - t0 )) s" >> "$log"
  return $rc
}
# why NAME: the last line a step printed (the tools end with their error), for the summary
why() { awk 'NF { line = $0 } END { print line }' "$work/$1.txt" 2>/dev/null | cut -c1-200; }
# key NAME FILE: the value of NAME=VALUE in FILE (gpu-tool's output)
key() { awk -F= -v k="$1" '$1 == k { sub(/^[^=]*=/, ""); print; exit }' "$2"; }
within() { awk -v v="$1" -v t="$2" 'BEGIN { print v != "" && v <= t ? "within" : "beyond" }'; }
verdict() {  # verdict VALUE TARGET above|below: met / missed, only on the GPU
  [[ $device == gpu ]] || { echo "n/a on cpu"; return; }
  awk -v v="$1" -v t="$2" -v d="$3" 'BEGIN { ok = d == "above" ? v >= t : v <= t; print ok ? "met" : "missed" }'
}

# ---- the driver: OpenCL through an ICD file of our own, EGL through glvnd's vendor file
# shellcheck source=tools/gpu-driver.sh
source "$(dirname "$0")/gpu-driver.sh"
say "$(date -u +%Y-%m-%dT%H:%M:%SZ) on ${HOSTNAME:-?}, device $device, $( ((quick)) && echo quick || echo full) mode, budget $budget s"
if [[ $device == gpu ]]; then
  gpu_driver_setup "$work" > "$work/driver.txt"  # not in a subshell: it exports
  while IFS= read -r line; do say "$line"; done < "$work/driver.txt"
fi
gpu_name=""
if [[ $device == gpu ]] && command -v nvidia-smi >/dev/null; then
  gpu_name=$(nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader 2>>"$log" | head -1) || true
  say "nvidia-smi: ${gpu_name:-(no answer)}"
fi
[[ -z ${BW_KERNEL_VECTOR_WIDTH:-} ]] || say "BW_KERNEL_VECTOR_WIDTH=$BW_KERNEL_VECTOR_WIDTH: kernels at that width"

# ---- bundle: the tools start (every library they need is there)
# The system's C++ runtime first; the bundle's where that one is missing or too old.
if ! gpu_cxx_runtime "$bundle" > "$work/runtime.txt"; then
  ldd "$B/bw-info" >> "$log" 2>&1 || true
  die "$B/bw-info does not start on this machine (ldd in $log)"
fi
say "$(cat "$work/runtime.txt")"

# ---- devices
if run_step devices-opencl 60 "$B/bw-sim" --device list; then
  cat "$work/devices-opencl.txt" >&2
  if ! grep -Eq "^ *[0-9]+  $device " "$work/devices-opencl.txt"; then
    failures+=("devices: no OpenCL $device device")
    say "no OpenCL $device device among those above"
  fi
  fig devices opencl_devices "$(grep -Ec '^ *[0-9]+  ' "$work/devices-opencl.txt")" count
else
  failures+=("devices: bw-sim --device list failed: $(why devices-opencl)")
fi
renderer="(none)"
if run_step devices-egl 60 "$B/gpu-tool" egl; then
  renderer=$(key gl_renderer "$work/devices-egl.txt")
  fig devices egl_devices "$(key egl_devices "$work/devices-egl.txt")" count
  say "OpenGL: $renderer ($(key gl_display "$work/devices-egl.txt")), $(key gl_version "$work/devices-egl.txt")"
  if [[ $device == gpu && $renderer == *llvmpipe* ]]; then
    failures+=("devices: EGL gave the software renderer ($renderer) on a GPU run")
  fi
else
  failures+=("devices: no EGL display with OpenGL 4.5: $(why devices-egl)")
fi
opencl=$(grep -E "^ *[0-9]+  $device " "$work/devices-opencl.txt" 2>/dev/null | head -1 | sed 's/^ *//') || true

# ---- agreement: the bundle's CPU reference of the dam break, run again here
agree_dir=$work/dambreak
if run_step agreement-sim 60 "$B/bw-sim" "$EX/dambreak.toml" -o "$agree_dir" \
     --device "$device" --quiet --end-time 0.3 --set time.frame_rate=20 --set "solid[0].particles=$REF/tank.h5"; then
  rc=0
  run_step agreement-frames 60 "$B/gpu-tool" frames "$REF/dambreak" "$agree_dir" --spacing 0.01 \
    --id-until "$tol_id_until" --max-rms "$tol_rms" --max-p99 "$tol_p99" --cell "$tol_cell" \
    --max-moved "$tol_moved" || rc=$?
  if (( rc == 0 || rc == 3 )); then
    a=$work/agreement-frames.txt
    fig agreement frames_compared "$(key frames "$a")" frames
    fig agreement particles_unmatched "$(key unmatched "$a")" particles 0
    fig agreement position_rms "$(key rms "$a")" "spacings by id at t = $(key id_time "$a") s" "$tol_rms" "" \
      "$(within "$(key rms "$a")" "$tol_rms")"
    fig agreement position_p99 "$(key p99 "$a")" "spacings by id at t = $(key id_time "$a") s" "$tol_p99" "" \
      "$(within "$(key p99 "$a")" "$tol_p99")"
    fig agreement position_max "$(key max "$a")" "spacings by id at t = $(key id_time "$a") s"
    fig agreement occupancy_moved "$(key moved "$a")" "of the particles in other cells of $tol_cell spacings at t = $(key time "$a") s" \
      "$tol_moved" "" "$(within "$(key moved "$a")" "$tol_moved")"
    fig agreement position_rms_last "$(key rms_last "$a")" "spacings by id at t = $(key time "$a") s (chaotic)"
    if (( rc == 3 )); then
      disagreements+=("frames: beyond the tolerance (by id RMS $(key rms "$a") p99 $(key p99 "$a") spacings; moved $(key moved "$a"))")
    fi
  else
    failures+=("agreement: gpu-tool frames exit $rc: $(why agreement-frames)")
  fi
else
  failures+=("agreement: bw-sim exit $?: $(why agreement-sim)")
fi
# The reference's frame drawn here. Its solids come from this machine's run of the
# same scene: the reference's run file names the tank's particles where the bundle
# was made.
if [[ ! -e $agree_dir/run.h5 ]]; then
  failures+=("agreement: no run of the dam break here to take the tank from; the image is not compared")
elif run_step agreement-render 60 "$B/bw-render" "$REF/dambreak/frames" -o "$work/dambreak-images" --frames 6:6 \
     --width 640 --height 360 --run "$agree_dir/run.h5"; then
  rc=0
  run_step agreement-images 30 "$B/gpu-tool" images "$REF/dambreak/images/000006.png" \
    "$work/dambreak-images/000006.png" --diff "$out/dambreak-diff.png" --max-mean "$tol_mean" \
    --max-share "$tol_share" || rc=$?
  if (( rc == 0 || rc == 3 )); then
    a=$work/agreement-images.txt
    fig agreement image_mean_difference "$(key mean "$a")" "levels of 255" "$tol_mean" "" \
      "$(within "$(key mean "$a")" "$tol_mean")"
    fig agreement image_share_over_32 "$(key share "$a")" "of the pixels" "$tol_share" "" \
      "$(within "$(key share "$a")" "$tol_share")"
    if (( rc == 3 )); then
      disagreements+=("image: beyond the tolerance (mean $(key mean "$a") levels; share $(key share "$a"))")
    fi
    cp "$REF/dambreak/images/000006.png" "$out/dambreak-cpu.png"
    cp "$work/dambreak-images/000006.png" "$out/dambreak-device.png"
  else
    failures+=("agreement: gpu-tool images exit $rc: $(why agreement-images)")
  fi
else
  failures+=("agreement: bw-render of the reference exit $?: $(why agreement-render)")
fi

# ---- bench-sim
bench_args=(--device "$device" --sizes "$sim_sizes" --csv "$work/bench-sim.csv")
(( quick )) && bench_args+=(--profile 0 --simulate 0)
rc=0
run_step bench-sim 200 "$B/bench-sim" "${bench_args[@]}" || rc=$?
if (( rc != 0 )); then
  failures+=("bench-sim: exit $rc: $(why bench-sim)")
fi
if [[ -s $work/bench-sim.csv ]]; then  # the sizes measured, also when it stopped at its limit
  # device,fluid,boundary,bytes_per_particle,best,median,cpu,ns_per_particle_step,setup_s,wall_per_simulated_s
  while IFS=, read -r _ fluid boundary bytes best median _ _ setup wps; do
    target="" paper="" v=""
    if (( fluid > 900000 && fluid < 1100000 )); then target=3e8; v=$(verdict "$best" 3e8 above); fi
    fig bench-sim "particle_steps_per_s_${fluid}" "$best" "particle-steps/s" "$target" "" "$v"
    fig bench-sim "particle_steps_per_s_median_${fluid}" "$median" "particle-steps/s"
    fig bench-sim "bytes_per_particle_${fluid}" "$bytes" "B"
    fig bench-sim "setup_${fluid}" "$setup" s
    [[ -n $wps ]] && fig bench-sim "wall_per_simulated_second_${fluid}" "$wps" s
  done < <(tail -n +2 "$work/bench-sim.csv")
fi

# ---- bench-render
if run_step bench-render 90 "$B/bench-render" $render_counts --csv "$work/bench-render.csv"; then
  # renderer,particles,ms_best,ms_median,draw_ms_best,png_ms_best,cpu_ms
  while IFS=, read -r _ n ms _ draw png _; do
    target="" v=""
    if (( n > 900000 )); then target=20; v=$(verdict "$draw" 20 below); fi
    fig bench-render "draw_ms_${n}" "$draw" "ms per 1280x720 frame (draw + read back)" "$target" "" "$v"
    fig bench-render "frame_ms_${n}" "$ms" "ms per frame (with PNG encoding)"
    fig bench-render "png_ms_${n}" "$png" "ms per PNG"
  done < <(tail -n +2 "$work/bench-render.csv")
else
  failures+=("bench-render: exit $?: $(why bench-render)")
fi

# ---- the paper's scenes: sample the meshes, simulate, measure steps per second
# scene NAME SPACING END LIMIT TARGET PAPER SOLID:VOLUME...
scene() {
  local name=$1 spacing=$2 end=$3 limit=$4 target=$5 paper=$6; shift 6
  local dir=$work/$name sets=() i=0 s mesh flag
  mkdir -p "$dir/particles"
  for s in "$@"; do
    mesh=${s%%:*} flag=${s#*:}
    run_step "$name-sample-$mesh" 120 "$B/bw-sample" "$EX/meshes/$mesh.obj" -o "$dir/particles/$mesh.h5" \
      --spacing "$spacing" $([[ $flag == volume ]] && echo --volume) || { failures+=("$name: bw-sample $mesh failed"); return; }
    sets+=(--set "solid[$i].particles=$dir/particles/$mesh.h5")
    i=$((i + 1))
  done
  local rc=0
  run_step "$name-sim" "$limit" "$B/bw-sim" "$EX/$name.toml" -o "$dir" --device "$device" --quiet \
    --set "spacing=$spacing" "${sets[@]}" --end-time "$end" || rc=$?
  if (( rc != 0 && rc != 124 )) || [[ ! -e $dir/run.h5 ]]; then failures+=("$name: bw-sim exit $rc: $(why "$name-sim")"); return; fi
  (( rc == 124 )) && say "$name: stopped at the step's time limit of $limit s; measured what it ran"
  run_step "$name-rate" 30 "$B/gpu-tool" rate "$dir/run.h5" --last 5 || { failures+=("$name: gpu-tool rate"); return; }
  local r=$work/$name-rate.txt sps
  sps=$(key steps_per_s_last "$r")
  fig "$name" spacing "$spacing" m
  fig "$name" simulated "$(key simulated "$r")" s
  fig "$name" fluid_at_end "$(key fluid "$r")" particles
  fig "$name" steps "$(key steps "$r")" steps
  fig "$name" steps_per_s_last_frames "$sps" "steps/s (last 5 frames)" "$target" "$paper" \
    "$( ((quick)) && echo "n/a in quick mode" || verdict "$sps" "$target" above)"
  fig "$name" steps_per_s_overall "$(key steps_per_s "$r")" "steps/s (frame 0 to the end)"
  fig "$name" particle_steps_per_s_last_frames "$(key particle_steps_per_s_last "$r")" "particle-steps/s"
  fig "$name" wall "$(key wall "$r")" s
}
scene wall "$wall_spacing" "$wall_end" 150 920 "92.1 fps (GTX 1660 Ti)" \
  ground:surface wall:volume

# ---- render: the wall run's last frames at 1280 x 720
if [[ -d $work/wall/frames ]]; then
  last=$(( $(ls "$work/wall/frames" | grep -c '^[0-9]*\.h5$') - 1 ))
  first=$(( last - render_frames + 1 < 0 ? 0 : last - render_frames + 1 ))
  if run_step render 90 "$B/bw-render" "$work/wall/frames" -o "$work/wall/images" \
       --frames "$first:$last" --scene "$EX/wall.toml" --width 1280 --height 720; then
    ms=$(sed -n 's/.*, \([0-9.]*\) ms per frame$/\1/p' "$work/render.txt" | tail -1)
    fig render ms_per_frame "${ms:-?}" "ms per 1280x720 frame of the wall (bw-render: read + draw + PNG + write)"
    fig render frames "$(( last - first + 1 ))" frames
    cp "$work/wall/images/$(printf %06d "$last").png" "$out/wall.png"
  else
    failures+=("render: bw-render exit $?: $(why render)")
  fi
else
  failures+=("render: no frames of the wall to draw")
fi

# ---- scene 3 last: the largest, it takes what is left of the budget
scene valley "$valley_spacing" "$valley_end" 240 212 "21.2 fps (GTX 1660 Ti)" \
  valley:surface dam:volume

# ---- summary: text, CSV (above) and JSON of every figure
awk -F, 'NR == 1 { next } { printf "%s{\"step\": \"%s\", \"figure\": \"%s\", \"value\": \"%s\", \"unit\": \"%s\", \"target\": \"%s\", \"paper\": \"%s\", \"verdict\": \"%s\"}", (NR > 2 ? ",\n  " : "[\n  "), $1, $2, $3, $4, $5, $6, $7 } END { print "\n]" }' "$csv" > "$out/figures.json"
{
  echo "gpu-check $(date -u +%Y-%m-%dT%H:%M:%SZ) on ${HOSTNAME:-?}: device $device, $( ((quick)) && echo quick || echo full) mode, $(( SECONDS - start )) s"
  echo "bundle: $(head -1 "$REF/made-on.txt" 2>/dev/null)"
  [[ -z $gpu_name ]] || echo "GPU: $gpu_name"
  echo "OpenCL: ${opencl:-(none)}"
  echo "OpenGL: $renderer"
  echo
  awk -F, '{ printf "%-13s %-40s %-14s %-28s %-8s %-24s %s\n", $1, $2, $3, $4, $5, $6, $7 }' "$csv"
  echo
  if [[ ${#failures[@]} -eq 0 && ${#disagreements[@]} -eq 0 ]]; then echo "every step ran; the device agrees with the CPU reference"; fi
  for f in "${failures[@]}"; do echo "FAILED: $f"; done
  for f in "${disagreements[@]}"; do echo "DISAGREES: $f"; done
} > "$out/summary.txt"
cat "$out/summary.txt" >&2
[[ ${#failures[@]} -eq 0 ]] || exit 1
[[ ${#disagreements[@]} -eq 0 ]] || exit 3
exit 0
