#!/usr/bin/env bash
# Installs every Debian package breakwater needs to build, test and run, on Debian
# 12 or a recent Ubuntu. Idempotent: installs only what is missing, so running it
# again costs a second. Uses sudo when not run as root.
#
#   tools/install-deps.sh           # build, test, simulate, render
#   tools/install-deps.sh --check   # exit 1 and list what is missing, install nothing
set -euo pipefail

packages=(
  # toolchain
  build-essential cmake ninja-build pkg-config
  # libraries
  libeigen3-dev libcgal-dev libgmp-dev libmpfr-dev libboost-dev
  libassimp-dev libhdf5-dev hdf5-tools libcli11-dev libtomlplusplus-dev libfmt-dev
  # compute: OpenCL headers, ICD loader and PoCL, the CPU device
  opencl-c-headers opencl-clhpp-headers ocl-icd-opencl-dev pocl-opencl-icd clinfo
  # rendering: EGL and OpenGL through Mesa (llvmpipe when there is no GPU), PNG
  libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri libpng-dev
  # export: OpenVDB level sets (on TBB's threads); Blender, the client the export's
  # test imports into
  libopenvdb-dev libtbb-dev blender
  # tests and benchmarks
  googletest libgtest-dev
  # videos and plots of the studies
  ffmpeg gnuplot-nox
  # ParaView: pvpython (python3-paraview, which brings paraview) opens runs in the tests
  python3-paraview
  # the GPU check's bundle (tools/gpu-bundle.sh): run paths, and the glvnd EGL/GL
  # libraries it carries to a machine that has only a GPU driver
  patchelf libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2 ocl-icd-libopencl1
  # Slurm (SCHEDULER=slurm, docs/cluster.md) and the single-node cluster its test starts
  slurm-wlm munge
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [[ ${#missing[@]} -eq 0 ]]; then
  exit 0
fi
if [[ "${1:-}" == "--check" ]]; then
  echo "missing packages: ${missing[*]}" >&2
  exit 1
fi

if ! command -v apt-get >/dev/null; then
  echo "install-deps: apt-get not found; install these packages by hand: ${missing[*]}" >&2
  exit 1
fi
sudo=()
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "install-deps: not root and no sudo; install: ${missing[*]}" >&2; exit 1; }
  sudo=(sudo)
fi
echo "install-deps: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -qq
"${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
