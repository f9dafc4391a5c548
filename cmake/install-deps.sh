#!/usr/bin/env bash
# Installs every Debian 12 package scansurf needs to build, run and test.
# Used by README's commands and by .ci/run; safe to run again (apt skips what is there).
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools glslang-tools
  nlohmann-json3-dev libcli11-dev libgtest-dev libgmock-dev
  libdraco-dev libeigen3-dev libpng-dev zlib1g-dev
  libdcmtk-dev libpugixml-dev libnifti2-dev libglm-dev libssl-dev
  clang-format  # tests/checks/format_check.sh (the build.format test)
  python3  # tests/checks/function_length.py (build.function_length) and tests/hostile/hostile.py
  pybind11-dev python3-dev python3-numpy  # the Python package (python/)
  python3-dask python3-distributed  # scansurf.batch on Dask
  python3-pytest python3-pydicom python3-meshio python3-jsonschema  # the Python tests (pydicom, interop, the report schema)
  dicom3tools  # dciodvfy: the tests validate the DICOM SEG output with it (skipped when missing)
  clang libclang-rt-14-dev  # .ci/run's sanitizer and fuzzing build (libFuzzer, ASan, UBSan runtimes)
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "scansurf: all build dependencies present"
  exit 0
fi
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
echo "scansurf: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
