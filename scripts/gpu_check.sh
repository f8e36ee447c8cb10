#!/usr/bin/env bash
# The GPU check (issue 14 item 13), for a machine with an NVIDIA GPU and nvcc: builds the `cuda`
# preset's gpu_check and runs it in double and in float (bench/gpu_check.cpp: the CUDA engine
# against the CPU engine on the 2D hydrostatic tank, the 2D dam break and the Terzaghi soil column;
# field differences and particle-steps per second of both). Prints everything; the output also goes
# to $OUT/gpu_check.txt when OUT is set (the device tool's folder). Exit status: gpu_check's worst.
#
# usage: bash scripts/gpu_check.sh [STEPS]   (default 500)
set -uo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
steps="${1:-500}"
log="${OUT:-build/cuda}/gpu_check.txt"
mkdir -p "$(dirname "$log")"
{
  nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv,noheader || echo "nvidia-smi: no GPU"
  lscpu | grep -m1 "Model name"
  cmake --preset cuda >/dev/null && cmake --build --preset cuda -j"$(nproc)" --target gpu_check >/dev/null || exit 2
  status=0
  for precision in double float; do
    build/cuda/bin/gpu_check --steps "$steps" --precision "$precision" || status=$?
  done
  exit "$status"
} 2>&1 | tee "$log"
exit "${PIPESTATUS[0]}"
