#!/usr/bin/env bash
# Renders every HMI screen in English, Chinese and Russian into docs/hmi/<lang>/
# with a live lasercncd on the simulated machine: touched off at X20 Y15 Z5,
# the bracket loaded and held at a single-block stop, the holes of
# share/examples/holes.csv in a scratch process database, the plate decomposed.
# Needs a built tree (build/); run from the checkout.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-docs/hmi}
work=$(mktemp -d)
shm=/lcnc_shots_$$
L=build/app/lasercnc
build/app/lasercncd --shm "$shm" --no-realtime --parameter-file "$work/p.var" >"$work/daemon.log" 2>&1 &
pid=$!
trap 'kill $pid 2>/dev/null || true; wait $pid 2>/dev/null || true; rm -rf "$work"' EXIT
for _ in $(seq 100); do $L status --shm "$shm" >/dev/null 2>&1 && break; sleep 0.05; done
$L send mdi "G0 X20 Y15 Z5" --wait --shm "$shm" >/dev/null
$L send mdi "G10 L20 P0 X0 Y0 Z0" --shm "$shm" >/dev/null
$L send load "$PWD/share/examples/bracket.ngc" --shm "$shm" >/dev/null
$L send start --single-block --shm "$shm" >/dev/null
for _ in 1 2; do
  until $L status --shm "$shm" | grep -q "single block"; do sleep 0.05; done
  $L send resume --shm "$shm" >/dev/null
  sleep 0.3
done
until $L status --shm "$shm" | grep -q "single block"; do sleep 0.05; done
for lang in en zh_CN ru; do
  rm -rf "${out:?}/$lang"
  QT_QPA_PLATFORM=offscreen build/hmi/lasercnc-hmi --db "$work/process.db" --shm "$shm" --lang "$lang" \
    --import share/examples/holes.csv --program share/examples/bracket.ngc \
    --dxf share/examples/plate_decompose.dxf --cut share/examples/plate_decompose.dxf \
    --screenshot "$out/$lang" >/dev/null
  rm -f "$work/process.db"
done
$L send stop --shm "$shm" >/dev/null
ls "$out"/*/*.png
