#!/usr/bin/env bash
# bench_fsi_modes.sh BUILD_DIR [THREADS]: fsi-modes on the 104 k DOF beam (beam_104k.toml) with
# the linear modes alone and with the reduced model of nonlinear_modal (5 modes + their 15
# modal derivatives, the cubic tensors), printing the stage's phase times. Measured, never
# asserted; run it on a quiet machine from a release build:
#   bash tests/benchmarks/modes/bench_fsi_modes.sh build/release 2
set -euo pipefail
build="$(cd "$1" && pwd)"
threads="${2:-1}"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
export OMP_NUM_THREADS="$threads" OPENBLAS_NUM_THREADS="$threads"
"$build/stages/fsi-mesh/fsi-mesh" "$here/beam_104k.toml" -o "$work/mesh.h5" -q
for derivatives in false true; do
  start=$(date +%s.%N)
  "$build/stages/fsi-modes/fsi-modes" "$here/beam_104k.toml" --mesh "$work/mesh.h5" \
    --set modes.derivatives=$derivatives --set modes.derivative_modes=5 -o "$work/modes.h5" 2>&1 |
    grep -E "phases \[s\]|reduced basis" | sed 's/^\[[^]]*\] info //' | cut -c1-260
  end=$(date +%s.%N)
  echo "modes.derivatives = $derivatives, $threads thread(s): $(awk "BEGIN { printf \"%.2f\", $end - $start }") s wall (process)"
done
