#!/bin/bash
# The training of a device run (devtools/train/device_run.py). Call 2's run.sh ends with it; a
# third call on the same warm machine runs it alone with RESUME=1 to go on from the last
# checkpoint (nothing to carry: this file travels with the repository):
#   RESUME=1 BUDGET_S=200 bash devtools/train/device_train.sh    (BUDGET_S: what the lease has left)
# The training's flags are call 2's ($W/train.args, written by run.sh). It keeps to BUDGET_S
# seconds from T0 (run.sh's start, else its own), EXPORT_S of them for the exports: the
# training stops at its own deadline (--until), validates and exports the best checkpoint;
# `timeout` is only the last resort (it signals the batch workers too, and a run it stops
# exports nothing itself). $OUT gets the log, history.json, the best and the last export.
set -x
T0=${T0:-$(date +%s)}
W=${W:-/tmp/w}
cd "$(dirname "$0")/../.."
[ -f "$W/train.args" ] || { echo "no $W/train.args: call 2 (run.sh) has not run on this machine"; exit 1; }
[ -n "$OUT" ] && [ -d "$OUT" ] || { echo "OUT names no folder"; exit 1; }
RESUME_ARGS=""
if [ "${RESUME:-0}" = 1 ]; then
  [ -f "$W/last.pt" ] || { echo "no $W/last.pt to go on from"; exit 1; }
  RESUME_ARGS="--resume $W/last.pt"
fi
export PYTHONUNBUFFERED=1 OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1
DEADLINE=$(( T0 + ${BUDGET_S:-590} - ${EXPORT_S:-60} ))
LEFT=$(( DEADLINE - $(date +%s) ))
[ $LEFT -lt 90 ] && { echo "only $LEFT s left: stopped"; exit 1; }
echo "training until $(date -u -d @$DEADLINE +%H:%M:%S), $LEFT s from now, set-up included"
# shellcheck disable=SC2046
timeout -s TERM $(( LEFT + 60 )) \
  python3 -m devtools.train $(cat "$W/train.args") $RESUME_ARGS --out "$OUT/roadsigns-gpu.onnx" \
  --until $(date -u -d @$DEADLINE +%Y-%m-%dT%H:%M:%S) 2>&1 \
  | grep --line-buffered -v -i '^\[ WARN\|UserWarning\|tensor.detach' | tee "$OUT/train.log"
cp "$W/history.json" "$OUT/" 2>/dev/null
python3 -m devtools.train --export-only "$W/last.pt" --out "$OUT/roadsigns-last.onnx" 2>&1 | tail -1
ls -la "$OUT"
