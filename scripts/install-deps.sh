#!/usr/bin/env bash
# Installs every Debian 12 package the project needs to build, test, run and plot.
# Idempotent and quiet when everything is already there. Run as root (or with sudo available).
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config git
  clang libclang-rt-14-dev            # libFuzzer target for the scenario parser
  libgtest-dev libgmock-dev libbenchmark-dev
  libyaml-cpp-dev nlohmann-json3-dev libcli11-dev libfmt-dev libtbb-dev
  libpugixml-dev                      # CommonRoad XML files (maneuvermap measure)
  libgoogle-perftools-dev             # tcmalloc, the executables' allocator (docs/performance.md)
  python3 python3-matplotlib python3-numpy
  python3-dev pybind11-dev python3-pytest  # the Python module maneuvermap and its tests (docs/python.md)
  python3-mypy  # its type stubs checked: mypy and stubtest (tests/python/CMakeLists.txt)
)
missing=()
for p in "${packages[@]}"; do
  [[ "$p" == \#* ]] && continue
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "installing: ${missing[*]}" >&2
  sudo=""
  [[ $(id -u) -ne 0 ]] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
