#!/usr/bin/env bash
# hil/vcan-run shares every path the command names: a run with an absolute --out outside the current directory
# (in the VM, only shared host directories are visible) must leave its outputs on the host, or fail. A success
# code with the outputs left in the VM was the defect this guards against.
#   vcan_run_out_test.sh SOURCE_DIR BUILD_DIR GYROSTAB
set -euo pipefail
src=$1 build=$2 bin=$3
out_root=$(mktemp -d /tmp/gyrostab-vcanrun-XXXXXX)
trap 'rm -rf "$out_root"' EXIT
cd "$build"
rc=0
GYROSTAB_PLOT_SCRIPT= "$src/hil/vcan-run" --build "$build" -- "$bin" run "$src/sim/scenes/monorail.toml" \
  --transport can --ticks 200 --no-progress --out "$out_root/deep/out" || rc=$?
if [ $rc -ne 0 ]; then echo "FAIL: vcan-run exited $rc"; exit 1; fi
for f in report.json signals.csv; do
  if [ ! -s "$out_root/deep/out/$f" ]; then echo "FAIL: $out_root/deep/out/$f is not on the host"; exit 1; fi
done
grep -q '"what_happened": "completed"' "$out_root/deep/out/report.json" || { echo "FAIL: the run did not complete"; exit 1; }
echo "ok: the outputs of an absolute --out reached the host"
