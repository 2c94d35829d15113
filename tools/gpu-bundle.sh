#!/usr/bin/env bash
# Makes a relocatable bundle of the built tools for a machine that has a GPU driver
# but none of the build's libraries (no Debian packages, no network): the tools and
# benchmarks stripped, every shared library they need beyond glibc (ICD loader and
# glvnd EGL/GL included) with run paths $ORIGIN/../lib, the example scenes and
# meshes, and a CPU reference of a short scene for tools/gpu-check.sh to compare the
# device's frames and images with. Prints the bundle's size; fails when it exceeds
# --max-mib (what may travel to the GPU machine, less room for the working tree).
#
#   tools/gpu-bundle.sh out/gpu-bundle                 # after cmake --build build
#   tools/gpu-bundle.sh out/gpu-bundle --tar              # also out/gpu-bundle.tar.gz
#   tools/gpu-bundle.sh out/gpu-bundle --build build-release --max-mib 56
#   make -f Makefile.scenes gpu-bundle                 # builds what it needs first
#
# Then on the GPU machine, from the repository's root:
#   tools/gpu-check.sh --bundle out/gpu-bundle --out OUTDIR
set -euo pipefail

usage() {
  sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'
  echo "Options: --build DIR (default build)  --max-mib N (default 56)  --tar (also OUTDIR.tar.gz, about 40% of the size)"
}
die() { echo "gpu-bundle: $1" >&2; exit "${2:-1}"; }

out="" build=build max_mib=56 tar=0
while [[ $# -gt 0 ]]; do
  case $1 in
    -h|--help) usage; exit 0 ;;
    --build) [[ $# -ge 2 ]] || die "--build needs a folder" 2; build=$2; shift 2 ;;
    --tar) tar=1; shift ;;
    --max-mib) [[ $# -ge 2 && $2 =~ ^[0-9]+$ ]] || die "--max-mib needs a whole number of MiB" 2; max_mib=$2; shift 2 ;;
    -*) die "unknown option '$1' (see --help)" 2 ;;
    *) [[ -z $out ]] || die "one output folder only ('$out', then '$1')" 2; out=$1; shift ;;
  esac
done
[[ -n $out ]] || die "no output folder given (tools/gpu-bundle.sh OUTDIR; see --help)" 2
root=$(cd "$(dirname "$0")/.." && pwd)
[[ $build = /* ]] || build=$root/$build
command -v patchelf >/dev/null || die "patchelf not found (tools/install-deps.sh installs it)" 2

# What the check runs, where the build puts it.
declare -A binary=(
  [bw-sim]=tools/bw-sim/bw-sim [bw-render]=tools/bw-render/bw-render [bw-sample]=tools/bw-sample/bw-sample
  [bw-info]=tools/bw-info/bw-info [bw-measure]=tools/bw-measure/bw-measure
  [bench-sim]=tests/bench/bench-sim [bench-render]=tests/bench/bench-render [gpu-tool]=tests/gpu/gpu-tool
)
for name in "${!binary[@]}"; do
  [[ -x $build/${binary[$name]} ]] ||
    die "$build/${binary[$name]}: not built (cmake --build $build --target ${!binary[*]})" 2
done

rm -rf "$out"
mkdir -p "$out/bin" "$out/lib" "$out/share"
out=$(cd "$out" && pwd)

# glibc's own libraries come with every Linux; everything else travels.
is_system() {
  case $1 in
    linux-vdso.so.*|ld-linux*|libc.so.*|libm.so.*|libpthread.so.*|libdl.so.*|librt.so.*|libresolv.so.*|libutil.so.*) return 0 ;;
  esac
  return 1
}
copy_libs_of() {  # the shared libraries $1 needs, by soname, into lib/
  local line soname path
  while read -r line; do
    [[ $line == *"=> not found"* ]] && die "$1 needs ${line%% *}, which is not installed here"
    [[ $line =~ ^([^[:space:]]+)[[:space:]]=\>[[:space:]]([^[:space:]]+) ]] || continue
    soname=${BASH_REMATCH[1]} path=${BASH_REMATCH[2]}
    is_system "$soname" && continue
    [[ -e $out/lib/$soname ]] || cp -L "$path" "$out/lib/$soname"
  done < <(ldd "$1")
}

for name in "${!binary[@]}"; do
  cp "$build/${binary[$name]}" "$out/bin/$name"
  strip --strip-unneeded "$out/bin/$name"
  copy_libs_of "$out/bin/$name"
done
# glvnd: libEGL dispatches to the driver's vendor library (the NVIDIA driver's EGL
# found through its egl_vendor.d file), which may want the other glvnd libraries.
for so in libEGL.so.1 libGLdispatch.so.0 libOpenGL.so.0 libGL.so.1 libGLX.so.0 libGLESv2.so.2; do
  path=$(ldconfig -p | awk -v so="$so" '$1 == so && /x86-64/ { print $NF; exit }')
  [[ -n $path ]] || die "$so not found (tools/install-deps.sh installs libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2)"
  [[ -e $out/lib/$so ]] || cp -L "$path" "$out/lib/$so"
done
for lib in "$out"/lib/*; do copy_libs_of "$lib"; done
# The C++ runtime of the build needs a glibc as new as the build's (2.36 on Debian
# 12), and every system has one of its own: the system's first, the bundle's only
# where that one is missing or too old (gpu-check.sh tries).
mkdir -p "$out/lib/fallback"
for so in libstdc++.so.6 libgcc_s.so.1; do
  [[ -e $out/lib/$so ]] && mv "$out/lib/$so" "$out/lib/fallback/"
done
for lib in "$out"/lib/*.so* "$out"/lib/fallback/*; do
  strip --strip-unneeded "$lib"
  patchelf --set-rpath '$ORIGIN' "$lib"
done
for bin in "$out"/bin/*; do patchelf --set-rpath '$ORIGIN/../lib' "$bin"; done

# The scenes the check runs and their meshes (the working tree may not be there).
mkdir -p "$out/share/examples/meshes"
cp "$root"/examples/{wall,valley,dambreak}.toml "$out/share/examples/"
cp "$root"/examples/meshes/{ground,wall,valley,dam,tank}.obj "$out/share/examples/meshes/"
cp "$root/tools/gpu-check.sh" "$out/"

# The CPU reference of the agreement check: the dam break (3 k particles, spacing
# 0.01) for 0.3 s on this machine's CPU device, its frames with particle ids, and
# one frame drawn by this machine's renderer. gpu-check.sh runs the same on the
# device and compares (docs/performance.md, "On a GPU").
ref=$out/share/reference
mkdir -p "$ref"
"$out/bin/bw-sample" "$root/examples/meshes/tank.obj" -o "$ref/tank.h5" --spacing 0.01
# The reference itself runs at the device's preferred width, whatever the caller set.
env -u BW_KERNEL_VECTOR_WIDTH "$out/bin/bw-sim" "$out/share/examples/dambreak.toml" -o "$ref/dambreak" \
  --device cpu --quiet --end-time 0.3 --set time.frame_rate=20 --set "solid[0].particles=$ref/tank.h5"
"$out/bin/bw-render" "$ref/dambreak/frames" -o "$ref/dambreak/images" --frames 6:6 --width 640 --height 360 --quiet
"$out/bin/bw-info" "$ref/dambreak/run.h5" --brief > "$ref/dambreak/run.txt"
{
  echo "made $(date -u +%Y-%m-%dT%H:%M:%SZ) from $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo '?')"
  "$out/bin/bw-sim" --device list
  "$out/bin/gpu-tool" egl | grep -E '^gl_(display|renderer|version)='
} > "$ref/made-on.txt"

bytes=$(du -sb "$out" | cut -f1)
mib=$(( (bytes + 1048575) / 1048576 ))
echo "gpu-bundle: $out: $(ls "$out/bin" | wc -l) programs, $(find "$out/lib" -type f | wc -l) libraries, $mib MiB"
if (( tar )); then
  tar -C "$(dirname "$out")" -czf "$out.tar.gz.tmp" "$(basename "$out")"
  mv "$out.tar.gz.tmp" "$out.tar.gz"
  tmib=$(( ($(stat -c %s "$out.tar.gz") + 1048575) / 1048576 ))
  echo "gpu-bundle: $out.tar.gz: $tmib MiB (tools/gpu-check.sh --bundle $out.tar.gz unpacks it)"
  (( tmib <= max_mib )) || die "$out.tar.gz is $tmib MiB, more than --max-mib $max_mib"
else
  (( mib <= max_mib )) || die "$out is $mib MiB, more than --max-mib $max_mib (--tar makes a smaller file)"
fi
