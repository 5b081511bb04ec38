#!/usr/bin/env bash
# Builds the programs (lasercnc, lasercncd, lasercnc-devices, lasercnc-hmi)
# and runs the sample laser job on the simulated machine, printing its
# report.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh
scripts/configure.sh default
cmake --build build -j2 --target lasercnc lasercncd lasercnc-devices lasercnc-hmi
# --devices: the laser source and power meter as simulated Modbus devices on
# loopback (app/laser_link.h); the report ends with what they saw.
exec build/app/lasercnc run share/examples/bracket.ngc --devices "$@"
