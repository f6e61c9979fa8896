#!/usr/bin/env bash
# GPU check on a machine with an NVIDIA GPU (Documentation/Benchmarks-GPU.md): the Vulkan
# device, the parity of the GPU and CPU press curves on the NVIDIA driver, and throughput.
#
#   bash scripts/gpu_check.sh pack   # here (Debian 12): build, collect what travels in .gpucheck/
#   bash scripts/gpu_check.sh run    # there: prints everything, writes $OUT/gpu_check.txt
#
# 'pack' builds rockdem_bench_solver and rockdem_gpu_parity (they need only the C and C++
# runtimes and libgomp) and downloads the Vulkan loader (libvulkan1) and vulkaninfo
# (vulkan-tools) as Debian packages, for a machine that has the NVIDIA driver but no
# loader. 'run' unpacks them, points the loader at NVIDIA's ICD when none is found, and
# runs, in a few minutes:
#   1. vulkaninfo --summary;
#   2. rockdem_gpu_parity: a consolidated, cemented specimen of about 3,000 particles
#      under unconfined compression to past its peak, on the CPU and on the GPU: the peak
#      stress, Young's modulus at 50 % of the peak and the strain at the peak within 1 %
#      (or bitwise identical);
#   3. throughput, rockdem_bench_solver: settled pack (lattice) and cemented specimen under
#      compression at 1M and 4M particles on the GPU, and on the CPU with 16 threads at
#      1M. Targets (issue 15): >= 1e9 particle-steps/s on the cemented specimen at >= 1M
#      particles, and >= 20x the 16-core CPU run.
# Device tool (DEVELOPERS notes): carry .gpucheck, e.g.
#   run(command="bash scripts/gpu_check.sh run", carry=[".gpucheck"], timeout_s=540)
set -uo pipefail
cd "$(dirname "$0")/.."
ROOT=$(pwd)
KIT="$ROOT/.gpucheck"

pack() {
  set -e
  cmake --build build --target rockdem_bench_solver rockdem_gpu_parity -j2
  rm -rf "$KIT" && mkdir -p "$KIT/bin" "$KIT/deb"
  cp build/bin/rockdem_bench_solver build/bin/rockdem_gpu_parity "$KIT/bin/"
  local exclude
  exclude=$(git rev-parse --git-path info/exclude) # .gpucheck/ travels only when ignored
  grep -qx '/.gpucheck/' "$exclude" 2>/dev/null || echo '/.gpucheck/' >> "$exclude"
  local lists=/tmp/gpucheck-apt
  mkdir -p "$lists/partial"
  local o="-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 -oDir::State::Lists=$lists"
  apt-get $o update -qq
  (cd "$KIT/deb" && apt-get $o download libvulkan1 vulkan-tools)
  du -sh "$KIT"
  echo "pack: ready in $KIT (carry it to the GPU machine)"
}

run() {
  local out="${OUT:-$ROOT}"
  local log="$out/gpu_check.txt"
  : > "$log"
  say() { echo "$@" | tee -a "$log"; }
  section() { say ""; say "=== $*"; }
  if ! ldconfig -p 2>/dev/null | grep -q 'libvulkan\.so\.1'; then
    for f in "$KIT"/deb/libvulkan1_*.deb; do [ -e "$f" ] && dpkg -x "$f" /; done
    ldconfig || true
  fi
  mkdir -p /tmp/vt && for f in "$KIT"/deb/vulkan-tools_*.deb; do [ -e "$f" ] && dpkg -x "$f" /tmp/vt; done
  local icd=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
  if [ -z "${VK_DRIVER_FILES:-}${VK_ICD_FILENAMES:-}" ] && [ -e "$icd" ] && \
     ! ls /usr/share/vulkan/icd.d/nvidia* /etc/vulkan/icd.d/nvidia* >/dev/null 2>&1; then
    export VK_DRIVER_FILES="$icd"
  fi
  section "machine"
  { nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv 2>&1 || true; nproc; } | tee -a "$log"
  section "vulkaninfo --summary"
  (vulkaninfo --summary 2>&1 || /tmp/vt/usr/bin/vulkaninfo --summary 2>&1 || echo "vulkaninfo not available") | tee -a "$log"
  section "parity: press test on the CPU and on the GPU (curve within 1 %)"
  timeout 200 "$KIT/bin/rockdem_gpu_parity" --particles 3000 2>&1 | tee -a "$log"
  section "throughput: GPU, settled pack and cemented specimen under compression, 1M and 4M particles"
  timeout 200 "$KIT/bin/rockdem_bench_solver" --sizes 1000000,4000000 --steps 200 --packs lattice,cemented \
    --backend gpu 2>&1 | tee -a "$log"
  section "throughput: CPU, 16 threads, 1M particles"
  timeout 120 "$KIT/bin/rockdem_bench_solver" --sizes 1000000 --steps 20 --packs lattice,cemented \
    --backend cpu --threads 16 2>&1 | tee -a "$log"
  say ""
  say "gpu_check: done; log in $log"
}

case "${1:-}" in
  pack) pack ;;
  run) run ;;
  *) echo "usage: bash scripts/gpu_check.sh pack|run" >&2; exit 2 ;;
esac
