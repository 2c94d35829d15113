#!/usr/bin/env bash
# gpu_check_quick: tools/gpu-bundle.sh --tar, then tools/gpu-check.sh --quick --device
# cpu on this machine from the tarball, and checks that the bundle is relocatable and
# that every output is there and sane; then tools/gpu-spheric.sh, briefly.
#   gpu_check_test.sh SOURCE_DIR BUILD_DIR WORK_DIR
set -euo pipefail
src=$1 build=$2 work=$3
fail() { echo "gpu_check_quick: $*" >&2; exit 1; }
rm -rf "$work"
mkdir -p "$work"
bundle=$work/bundle out=$work/out

"$src/tools/gpu-bundle.sh" "$bundle" --build "$build" --tar | tee "$work/bundle.txt"
grep -Eq '^gpu-bundle: .*, [0-9]+ MiB$' "$work/bundle.txt" || fail "gpu-bundle printed no size"
[[ -s $bundle.tar.gz ]] || fail "gpu-bundle --tar made no $bundle.tar.gz"

# Relocatable: every binary looks in ../lib first, and every library it needs beyond
# glibc resolves there.
for bin in "$bundle"/bin/*; do
  readelf -d "$bin" | grep -q 'R.*PATH.*\[\$ORIGIN/../lib\]' || fail "$bin: run path is not \$ORIGIN/../lib"
  while read -r soname _ path _; do
    case $soname in linux-vdso*|ld-linux*|libc.so*|libm.so*|libpthread*|libdl.so*|librt.so*|libresolv*|libutil*) continue ;; esac
    # The C++ runtime: the system's first (lib/fallback holds the build's).
    case $soname in libstdc++.so.6|libgcc_s.so.1)
      [[ -e $bundle/lib/fallback/$soname ]] || fail "$bundle/lib/fallback/$soname is missing"; continue ;;
    esac
    path=$(realpath "$path")
    [[ $path == "$bundle/lib/"* ]] || fail "$bin: $soname resolves to $path, outside the bundle"
  done < <(ldd "$bin" | grep '=>')
done

# Nothing may refer to where the bundle was made: the check runs from the tarball
# with the folder gone.
rm -rf "$bundle"
rc=0
"$src/tools/gpu-check.sh" --bundle "$bundle.tar.gz" --out "$out" --quick --device cpu --work "$work/runs" || rc=$?
[[ $rc -eq 0 ]] || fail "gpu-check.sh exited with $rc (summary: $out/summary.txt)"

for f in summary.txt figures.csv figures.json gpu-check.log wall.png dambreak-cpu.png dambreak-device.png dambreak-diff.png; do
  [[ -s $out/$f ]] || fail "$out/$f is missing or empty"
done
[[ $(ls "$out" | wc -l) -le 8 ]] || fail "$out holds more than 8 files"
for png in "$out"/*.png; do
  [[ $(head -c 8 "$png" | od -An -tx1 | tr -d ' \n') == 89504e470d0a1a0a ]] || fail "$png is not a PNG"
done
python3 -c 'import json, sys; rows = json.load(open(sys.argv[1])); assert len(rows) > 20, len(rows)' \
  "$out/figures.json" || fail "$out/figures.json is not the JSON of the figures"

# figure STEP NAME: its value in figures.csv
figure() { awk -F, -v s="$1" -v n="$2" '$1 == s && $2 == n { print $3; found = 1 } END { exit !found }' "$out/figures.csv"; }
positive() {
  local v; v=$(figure "$1" "$2") || fail "figures.csv has no $1 $2"
  awk -v v="$v" 'BEGIN { exit !(v + 0 > 0) }' || fail "$1 $2 = '$v', not a positive number"
}
at_most() {
  local v; v=$(figure "$1" "$2") || fail "figures.csv has no $1 $2"
  awk -v v="$v" -v m="$3" 'BEGIN { exit !(v != "" && v + 0 >= 0 && v + 0 <= m) }' || fail "$1 $2 = '$v', not in [0, $3]"
}
grep -q '^bench-sim,particle_steps_per_s_' "$out/figures.csv" || fail "no bench-sim figures"
while IFS=, read -r _ name value _; do
  awk -v v="$value" 'BEGIN { exit !(v + 0 > 1e5) }' || fail "bench-sim $name = $value, implausibly slow"
done < <(grep '^bench-sim,particle_steps_per_s_[0-9]' "$out/figures.csv")
grep -q '^bench-render,draw_ms_' "$out/figures.csv" || fail "no bench-render figures"
for scene in wall valley; do
  positive "$scene" fluid_at_end
  positive "$scene" steps_per_s_last_frames
  positive "$scene" particle_steps_per_s_last_frames
done
positive render ms_per_frame
at_most agreement particles_unmatched 0
# The tolerances of gpu-check.sh, and a difference there at all: the runs differ in
# rounding (BW_KERNEL_VECTOR_WIDTH), not bit-identical.
at_most agreement position_rms 0.05
at_most agreement position_p99 0.2
at_most agreement occupancy_moved 0.08
at_most agreement image_mean_difference 4
if [[ ${BW_KERNEL_VECTOR_WIDTH:-} == 1 ]]; then
  positive agreement position_rms
fi
grep -q 'every step ran; the device agrees with the CPU reference' "$out/summary.txt" || fail "summary.txt: not every step ran"
# tools/gpu-spheric.sh from the same tarball: SPHERIC Test 2 at a coarse spacing for
# 0.05 s (before the water reaches the box), a draw (fluid.seed 3) at two widths:
# each run's report and the spread over them.
sph=$work/spheric
rc=0
"$src/tools/gpu-spheric.sh" --bundle "$bundle.tar.gz" --out "$sph" --device cpu --spacings 0.04 --diffusion 0.2 \
  --widths 1,2 --seeds 3 --end 0.05 --frames 20 --budget 200 --work "$work/spheric-runs" || rc=$?
[[ $rc -eq 0 ]] || fail "gpu-spheric.sh exited with $rc ($sph/gpu-spheric.log)"
for f in runs.csv summary.md gpu-spheric.log 0.04/d0.2-w1-s3/sensors.csv 0.04/d0.2-w2-s3/spheric2.md \
         0.04/d0.2/spheric2-spread.md; do
  [[ -s $sph/$f ]] || fail "$sph/$f is missing or empty"
done
[[ $(awk -F, 'NR > 1 && $1 == "0.04" && $2 == "0.2" && $4 == "0" && $6 == "0.05" && $8 > 9000 && $10 == 3' "$sph/runs.csv" | wc -l) -eq 2 ]] ||
  fail "$sph/runs.csv: not two complete runs of seed 3 at 0.04 m to 0.05 s"
grep -q '^| P1 | 2 |' "$sph/0.04/d0.2/spheric2-spread.md" || fail "spheric2-spread.md: no row of P1 over the two runs"
rc=0
"$src/tools/gpu-spheric.sh" --bundle "$bundle.tar.gz" --out "$sph" --widths 3 2> "$work/usage.txt" || rc=$?
[[ $rc -eq 2 ]] && grep -q "widths: '3'" "$work/usage.txt" || fail "gpu-spheric.sh --widths 3: exit $rc, not 2 with the value named"
rc=0
"$src/tools/gpu-spheric.sh" --bundle "$bundle.tar.gz" --out "$sph" --seeds 1,x 2> "$work/usage.txt" || rc=$?
[[ $rc -eq 2 ]] && grep -q "seeds: 'x'" "$work/usage.txt" || fail "gpu-spheric.sh --seeds 1,x: exit $rc, not 2 with the value named"

echo "gpu_check_quick: bundle $(tail -1 "$work/bundle.txt" | sed 's/.*, //'), outputs in $out"
