#!/usr/bin/env bash
# One `urbanvec vectorize` run on a grid folder (landuse.tif, density.tif, parcels.tif, parcels.csv, as
# mirror_grid.py writes them), with the bench's options, printing CPU and wall seconds of every
# progress stage and the /usr/bin/time totals (issue 21: the per-stage before/after figures of
# docs/performance.md). CPU seconds are the figure to compare on a shared machine.
# Usage: bench/vectorize/stage_times.sh <urbanvec> <grid dir> <out.gpkg> <threads> [vectorize options]
set -euo pipefail
repo=$(cd "$(dirname "$0")/../.." && pwd)
[ $# -ge 4 ] || { sed -n '2,6p' "$0" | sed 's/^# \{0,1\}//'; exit 2; }
uv=$1 grid=$2 out=$3 threads=$4
shift 4
rm -f "$out"
log=${out%.gpkg}.log
{
  echo "$BASHPID" >"$out.pid"
  exec /usr/bin/time -f "TOTAL wall %e user %U sys %S maxrss_kb %M" -o "$out.time" "$uv" vectorize -timings \
    -progress lines -threads "$threads" "$@" -density "$grid/density.tif" -parcels "$grid/parcels.tif" \
    -parcel-table "$grid/parcels.csv" "$grid/landuse.tif" "$out" 2>/dev/null
} | /usr/bin/python3 "$repo/bench/vectorize/timestamp.py" "$out.pid" >"$log"
/usr/bin/python3 - "$log" <<'PY'
import sys
events = []  # (wall, cpu, stage) at each change of stage
for line in open(sys.argv[1]):
    parts = line.rstrip("\n").split(" ", 4)
    if len(parts) < 5:
        continue
    text = parts[4]
    stage = text.split(" ", 2)[2] if text.count(" ") >= 2 else text
    if not events or events[-1][2] != stage:
        events.append((float(parts[0]), float(parts[1]), stage))
totals, order = {}, []
for (w0, c0, stage), (w1, c1, _) in zip(events, events[1:]):
    if stage not in totals:
        totals[stage] = [0.0, 0.0]
        order.append(stage)
    totals[stage][0] += w1 - w0
    totals[stage][1] += c1 - c0
for stage in order:
    wall, cpu = totals[stage]
    if wall > 0.05:
        print(f"{stage[:40]:40s} wall {wall:7.2f} cpu {cpu:7.2f} ({100 * cpu / wall:.0f}%)")
PY
cat "$out.time"
echo "load average at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
