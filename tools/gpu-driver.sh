# shellcheck shell=bash
# The GPU driver for the bundled tools (tools/gpu-bundle.sh), sourced by
# tools/gpu-check.sh and tools/gpu-spheric.sh. On a machine with only a GPU driver
# installed, OpenCL goes through an ICD file of our own that names the driver's
# libnvidia-opencl.so.1 (the bundle's ICD loader reads OCL_ICD_VENDORS), and glvnd's
# EGL through the driver's vendor file (or one of our own naming libEGL_nvidia.so.0);
# a driver folder the loader's cache does not know goes on LD_LIBRARY_PATH.
#
#   gpu_driver_setup WORK    exports the variables; WORK holds the files made
#   gpu_cxx_runtime BUNDLE   the system's C++ runtime, or the bundle's fallback where
#                            that one is missing or older than the build's
# Both print what they did, one line each, on stdout.

# The path of a shared library: the loader's cache, then the usual folders.
gpu_find_lib() {
  local so=$1 path d
  path=$(ldconfig -p 2>/dev/null | awk -v so="$so" '$1 == so && /x86-64/ { print $NF; exit }')
  [[ -n $path ]] && { echo "$path"; return; }
  for d in /usr/lib/x86_64-linux-gnu /usr/local/nvidia/lib64 /usr/local/nvidia/lib /usr/lib64 /usr/lib \
           /usr/local/cuda/compat /usr/lib/x86_64-linux-gnu/nvidia/current; do
    [[ -e $d/$so ]] && { echo "$d/$so"; return; }
  done
  return 1
}

# A driver folder the loader's cache does not know goes on the search path, for the
# libraries the driver's own libraries load by name.
gpu_search_driver_folder() {
  local dir; dir=$(dirname "$1")
  ldconfig -p 2>/dev/null | grep -q " => $dir/" && return 0
  [[ :${LD_LIBRARY_PATH:-}: == *:$dir:* ]] || export LD_LIBRARY_PATH=$dir${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
}

gpu_driver_setup() {
  local work=$1 cl egl f
  if cl=$(gpu_find_lib libnvidia-opencl.so.1); then
    mkdir -p "$work/icd"
    echo "$cl" > "$work/icd/nvidia.icd"
    export OCL_ICD_VENDORS=$work/icd
    gpu_search_driver_folder "$cl"
    echo "OpenCL: $cl through $work/icd/nvidia.icd"
  else
    echo "OpenCL: no libnvidia-opencl.so.1 found; the ICD loader's own files (/etc/OpenCL/vendors) decide"
  fi
  if [[ -z ${__EGL_VENDOR_LIBRARY_FILENAMES:-} ]]; then
    for f in /usr/share/glvnd/egl_vendor.d/10_nvidia.json /etc/glvnd/egl_vendor.d/10_nvidia.json \
             /usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json /usr/local/share/glvnd/egl_vendor.d/10_nvidia.json; do
      [[ -e $f ]] && { export __EGL_VENDOR_LIBRARY_FILENAMES=$f; break; }
    done
  fi
  if egl=$(gpu_find_lib libEGL_nvidia.so.0); then
    gpu_search_driver_folder "$egl"
    if [[ -z ${__EGL_VENDOR_LIBRARY_FILENAMES:-} ]]; then
      # No vendor file installed: one of our own naming the driver's EGL library.
      printf '{"file_format_version": "1.0.0", "ICD": {"library_path": "%s"}}\n' "$egl" > "$work/10_nvidia.json"
      export __EGL_VENDOR_LIBRARY_FILENAMES=$work/10_nvidia.json
    fi
  fi
  echo "EGL vendor file: ${__EGL_VENDOR_LIBRARY_FILENAMES:-the default folders of glvnd}; LD_LIBRARY_PATH=${LD_LIBRARY_PATH:-}"
}

# Returns 1 when the bundle's tools start with neither runtime (ldd says why).
gpu_cxx_runtime() {
  local bundle=$1
  "$bundle/bin/bw-info" --version > /dev/null 2>&1 && { echo "C++ runtime: the system's"; return 0; }
  export LD_LIBRARY_PATH=$bundle/lib/fallback${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
  "$bundle/bin/bw-info" --version > /dev/null 2>&1 || return 1
  echo "C++ runtime: the system's is missing or older than the build's: the bundle's ($bundle/lib/fallback)"
}
