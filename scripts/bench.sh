#!/usr/bin/env bash
# Benchmark of `urbanvec vectorize` at city scale (issue 8; results and how to read them in
# docs/performance.md). For the sample grids and for large grids mirrored from one of them
# (bench/vectorize/mirror_grid.py: tiles flipped so roads continue across tile edges, with density,
# parcel ids unique per tile and a consistent parcel table), it measures, back to back on the same
# landuse.tif:
#   gdal_polygonize.py to a GeoPackage (as bench/baselines/polygonize.sh runs it),
#   GRASS r.in.gdal + r.to.vect type=area + v.out.ogr to a GeoPackage,
#   urbanvec vectorize with density, parcels and parcel table, end to end and per stage,
# each under /usr/bin/time -v (wall, user and system CPU, peak resident memory), and prints the
# tables: figures per grid, ratios to the baselines, memory against input + output, the scaling of
# time per million cells, and wall time and CPU utilisation per stage.
#
# Usage: scripts/bench.sh [options]
#   --urbanvec PATH   the urbanvec program (default: $URBANVEC, else build/bin/urbanvec made by
#                     scripts/build.sh)
#   --work DIR        grids, outputs and logs (default: $BENCH_WORK, else ${TMPDIR:-/tmp}/urbanvec-bench)
#   --sizes "N ..."   cells per side of the mirrored grids (default: "1024 2048 4096")
#   --city NAME       sample city the large grids are mirrored from: monaco or bubenec (default monaco)
#   --no-samples      skip the two sample grids themselves
#   --no-grass        skip GRASS (e.g. where grass-core is not installed)
#   --threads N       vectorize -threads (default 0 = all cores)
#   --markdown FILE   also write the tables as Markdown to FILE
#   --smoke           a quick check of the whole chain: --sizes 256 --no-samples (a few seconds)
# Needs gdal-bin, python3-gdal (with numpy) and grass-core (scripts/setup.sh installs them) and
# /usr/bin/time. Wall times are noisy on a shared machine: compare the CPU seconds as well.
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
PY=/usr/bin/python3  # Debian's python3 with python3-gdal, whatever python3 is first on PATH

usage() { sed -n '2,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//'; }

urbanvec=${URBANVEC:-}
work=${BENCH_WORK:-${TMPDIR:-/tmp}/urbanvec-bench}
sizes="1024 2048 4096"
city=monaco
samples=1
grass=1
threads=0
markdown=""
while [ $# -gt 0 ]; do
  case "$1" in
    --urbanvec) urbanvec=$2; shift 2 ;;
    --work) work=$2; shift 2 ;;
    --sizes) sizes=$2; shift 2 ;;
    --city) city=$2; shift 2 ;;
    --no-samples) samples=0; shift ;;
    --no-grass) grass=0; shift ;;
    --threads) threads=$2; shift 2 ;;
    --markdown) markdown=$2; shift 2 ;;
    --smoke) sizes=256; samples=0; shift ;;
    -h | --help) usage; exit 0 ;;
    *) echo "ERROR: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
case "$city" in monaco | bubenec) ;; *) echo "ERROR: --city must be monaco or bubenec, got '$city'" >&2; exit 2 ;; esac
for n in $sizes; do
  [[ "$n" =~ ^[0-9]+$ ]] && [ "$n" -ge 16 ] || { echo "ERROR: --sizes takes whole numbers >= 16, got '$n'" >&2; exit 2; }
done

[ -x /usr/bin/time ] || { echo "ERROR: /usr/bin/time is not installed (Debian package 'time')" >&2; exit 1; }
command -v gdal_polygonize.py >/dev/null || { echo "ERROR: gdal_polygonize.py is not installed (gdal-bin, python3-gdal)" >&2; exit 1; }
"$PY" -c 'import numpy; from osgeo import gdal' 2>/dev/null ||
  { echo "ERROR: $PY cannot import numpy and osgeo.gdal (python3-gdal, python3-numpy)" >&2; exit 1; }
if [ "$grass" -eq 1 ] && ! command -v grass >/dev/null; then
  echo "ERROR: GRASS GIS ('grass', Debian grass-core) is not installed; use --no-grass to skip it" >&2
  exit 1
fi
if [ -z "$urbanvec" ]; then
  bash "$repo/scripts/build.sh"
  urbanvec="$repo/build/bin/urbanvec"
fi
[ -x "$urbanvec" ] || { echo "ERROR: urbanvec program '$urbanvec' is not executable" >&2; exit 1; }
urbanvec=$(realpath "$urbanvec")

mkdir -p "$work/grids" "$work/runs"
work=$(realpath "$work")
results="$work/results.tsv"
printf 'grid\tcells\tinput_bytes\ttool\twall_s\tuser_s\tsys_s\tpeak_kb\toutput_bytes\tstatus\n' >"$results"
{
  echo "date: $(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "cpus: $(nproc)"
  echo "cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')"
  echo "memory: $(awk '/MemTotal/ {printf "%.1f GiB", $2 / 1048576}' /proc/meminfo)"
  echo "urbanvec: $("$urbanvec" --version 2>/dev/null | head -1)"
  echo "gdal: $(gdalinfo --version)"
  [ "$grass" -eq 0 ] || echo "grass: $(grass --version 2>&1 | head -1)"
  echo "urbanvec_idle_kb: $(/usr/bin/time -f %M "$urbanvec" vectorize --help 2>&1 >/dev/null | tail -1)"
  echo "load_start: $(cut -d' ' -f1-3 /proc/loadavg)"
} >"$work/machine.txt"

# name:dir of every grid, sample grids first.
grids=()
if [ "$samples" -eq 1 ]; then
  grids+=("monaco:$repo/sample_data/monaco" "bubenec:$repo/sample_data/bubenec")
fi
for n in $sizes; do
  dir="$work/grids/${city}_$n"
  stamp="$dir/.made-by"
  want="$(sha1sum "$repo/bench/vectorize/mirror_grid.py" "$repo/sample_data/$city/"{landuse,density,parcels}.tif \
    "$repo/sample_data/$city/parcels.csv" | sha1sum | cut -c1-40) $n"
  if [ ! -f "$stamp" ] || [ "$(cat "$stamp")" != "$want" ]; then
    echo "== mirroring sample_data/$city into ${n} x ${n} cells"
    rm -rf "$dir"
    "$PY" "$repo/bench/vectorize/mirror_grid.py" "$repo/sample_data/$city" "$n" "$dir"
    echo "$want" >"$stamp"
  fi
  grids+=("${city}_$n:$dir")
done

# record <grid> <cells> <input bytes> <tool> <output> <status>: one row of results.tsv from the
# /usr/bin/time -v report in runs/<grid>_<tool>.time.
record() {
  local grid=$1 cells=$2 input=$3 tool=$4 output=$5 status=$6
  local run="$work/runs/${grid}_$tool"
  local wall user sys peak bytes=0
  wall=$(awk -F': ' '/Elapsed \(wall clock\)/ {n = split($2, t, ":"); s = 0; for (i = 1; i <= n; i++) s = s * 60 + t[i]; print s}' "$run.time")
  user=$(awk -F': ' '/User time/ {print $2}' "$run.time")
  sys=$(awk -F': ' '/System time/ {print $2}' "$run.time")
  peak=$(awk -F': ' '/Maximum resident set size/ {print $2}' "$run.time")
  [ -f "$output" ] && bytes=$(stat -c %s "$output")
  printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$grid" "$cells" "$input" "$tool" "$wall" "$user" "$sys" \
    "$peak" "$bytes" "$status" >>"$results"
  awk -v tool="$tool" -v wall="$wall" -v cpu="$(awk -v u="$user" -v s="$sys" 'BEGIN {print u + s}')" \
    -v peak="$peak" -v bytes="$bytes" -v status="$status" -v run="$run" 'BEGIN {
      printf "   %-20s wall %8.2f s  cpu %8.2f s  peak %7.1f MB  output %7.1f MB", tool, wall, cpu, peak / 1024, bytes / 1048576
      if (status != 0) printf "  FAILED (exit %d, see %s.*)", status, run
      printf "\n" }'
}

# measure <grid> <cells> <input bytes> <tool> <output> <command...>: one run under /usr/bin/time -v.
measure() {
  local grid=$1 cells=$2 input=$3 tool=$4 output=$5
  shift 5
  local status=0
  /usr/bin/time -v -o "$work/runs/${grid}_$tool.time" "$@" || status=$?
  record "$grid" "$cells" "$input" "$tool" "$output" "$status"
}

cat >"$work/runs/grass_steps.sh" <<'STEPS'
set -euo pipefail
r.in.gdal --quiet input="$BENCH_INPUT" output=landuse
g.region --quiet raster=landuse
r.to.vect --quiet input=landuse output=landuse_areas type=area
v.out.ogr --quiet input=landuse_areas type=area output="$BENCH_OUTPUT" format=GPKG output_layer=out
STEPS

for entry in "${grids[@]}"; do
  grid=${entry%%:*}
  dir=${entry#*:}
  read -r width height < <(gdalinfo "$dir/landuse.tif" | awk '/^Size is/ {gsub(",", ""); print $3, $4}')
  cells=$((width * height))
  # Input as the program holds it: Byte land use + Float32 density + Int32 parcel ids, plus the table.
  input=$((cells * 9 + $(stat -c %s "$dir/parcels.csv")))
  echo "== $grid: $width x $height cells"
  out="$work/runs/$grid"

  rm -f "$out.polygonize.gpkg"
  measure "$grid" "$cells" "$input" gdal_polygonize "$out.polygonize.gpkg" \
    gdal_polygonize.py -q "$dir/landuse.tif" -f GPKG "$out.polygonize.gpkg" out DN

  if [ "$grass" -eq 1 ]; then
    rm -f "$out.grass.gpkg"
    BENCH_INPUT="$dir/landuse.tif" BENCH_OUTPUT="$out.grass.gpkg" \
      measure "$grid" "$cells" "$input" grass_r.to.vect "$out.grass.gpkg" \
      bash -c 'exec grass --tmp-location "$BENCH_INPUT" --exec bash "$0" >"$1" 2>&1' \
      "$work/runs/grass_steps.sh" "$out.grass.log"
  fi

  # vectorize under /usr/bin/time, its stdout (progress lines and the -timings table) through the
  # timestamp filter, which also reads the process's CPU time at every line (the pid file names the
  # time process; the filter follows it to its child).
  tool=urbanvec_vectorize
  run="$work/runs/${grid}_$tool"
  rm -f "$out.vectorize.gpkg" "$run.pid"
  status=0
  {
    echo "$BASHPID" >"$run.pid"
    exec /usr/bin/time -v -o "$run.time" "$urbanvec" vectorize -timings -progress lines -threads "$threads" \
      -density "$dir/density.tif" -parcels "$dir/parcels.tif" -parcel-table "$dir/parcels.csv" \
      "$dir/landuse.tif" "$out.vectorize.gpkg" 2>"$run.stderr"
  } | "$PY" "$repo/bench/vectorize/timestamp.py" "$run.pid" >"$run.log" || status=$?
  record "$grid" "$cells" "$input" "$tool" "$out.vectorize.gpkg" "$status"
done
echo "load_end: $(cut -d' ' -f1-3 /proc/loadavg)" >>"$work/machine.txt"

echo
report=("$PY" "$repo/bench/vectorize/report.py" "$work")
[ -n "$markdown" ] && report+=(--markdown "$markdown")
"${report[@]}"

# Streets (issue 18): synthetic 25, 100 and 400 km² cities, wall time and peak memory (docs/performance.md).
if [ "${BENCH_STREETS:-1}" = 1 ]; then
  echo
  echo "urbanvec streets:"
  URBANVEC="$urbanvec" bash "$repo/bench/streets/speed.sh" "$threads"
fi
