#!/usr/bin/env bash
# Installs the Debian 12 packages LaserCNC builds and tests with, when missing.
# Needs root (or sudo) only when something is missing.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  ccache                   # scripts/test.sh: a rebuild compiles only what changed, in any tree
  clang-format clang-tidy python3  # scripts/lint.sh: the house style and checks (.clang-format, .clang-tidy)
  libeigen3-dev            # geometry (docs/design.md §3)
  libtomlplusplus-dev      # machine config (TOML)
  libspdlog-dev            # logging outside the RT path
  nlohmann-json3-dev       # --json report
  libgtest-dev libgmock-dev
  libdxflib-dev            # DXF input
  libpolyclipping-dev      # Clipper: kerf offset of lasercnc cut (core/cut)
  libmodbus-dev            # peripherals
  qtbase5-dev libqt5sql5-sqlite  # HMI, process DB
  qttools5-dev qttools5-dev-tools  # the HMI's translations (Qt Linguist: lupdate, lrelease)
  fonts-dejavu-core fonts-wqy-microhei  # the HMI's fonts, by name (hmi/hmi_font.h)
  fonts-urw-base35 xfonts-base  # tests: the HMI's layout with fonts it does not use installed
  ghdl                     # hdl/: VHDL-2008 simulation of the interpolator
  linuxcnc-uspace linuxcnc-uspace-dev  # LinuxCNC's HAL: real drives (drivers/hal/), the hal tests
  rt-tests                 # cyclictest: the RT latency reference (bench/rt_latency_vs_cyclictest.sh)
  debootstrap              # the package test: a clean Debian 12 to install the .deb in (tests/package)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "deps: installing ${missing[*]}" >&2
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
