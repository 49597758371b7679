#!/usr/bin/env bash
# Nothing a user owns is ever lost (issue 15): -overwrite replaces only what a run writes, an output
# never replaces an input, multi-file formats are written atomically, concurrent runs on one name,
# signals at each phase of writing, stale temporaries of killed runs, and injected write faults.
set -euo pipefail
source "$(dirname "$0")/lib.sh"

BUB="$SAMPLE_DIR/bubenec"
MON="$SAMPLE_DIR/monaco"
PBF="$SAMPLE_DIR/sources/monaco.osm.pbf"
cd "$WORK"

# No staging folder and no lock file may be left after a run ends.
expect_clean() {
  expect_no_temp "$1"
  if ls -a "$1" | grep -q '\.lock$'; then fail "lock file left in $1"; fi
}
checksums() { (cd "$1" && find . -type f -print0 | sort -z | xargs -0 sha1sum); }
listing() { (cd "$1" && find . | sort); }

# --- gridify -overwrite replaces its own five files and nothing else -------------------------------
mkdir -p grid/sub
echo "my notes" >grid/notes.txt
echo "dot" >grid/.hidden
echo "deep" >grid/sub/file
run_cmd gridify -q -tr 24 "$PBF" grid
expect_status 0
for f in landuse.tif density.tif parcels.tif parcels.csv truth.gpkg; do expect_exists "grid/$f"; done
before=$(checksums grid | grep -v -e landuse -e density -e parcels -e truth)
run_cmd gridify -q -tr 24 "$PBF" grid
expect_status 1
expect_stderr "ERROR: output folder 'grid' already holds landuse.tif, density.tif, parcels.tif, parcels.csv, truth.gpkg; use -overwrite to replace them (other files in the folder are kept)"
echo '<PAMDataset/>' >grid/landuse.tif.aux.xml  # what QGIS leaves beside a raster it opened
run_cmd gridify -q -overwrite -tr 30 "$PBF" grid
expect_status 0
expect_eq "$(checksums grid | grep -v -e landuse -e density -e parcels -e truth)" "$before" "files gridify does not write"
expect_missing grid/landuse.tif.aux.xml  # stale statistics of the replaced raster go with it
expect_eq "$(gdalinfo grid/landuse.tif | sed -n 's/^Pixel Size = (\([0-9.]*\),.*/\1/p')" "30.000000000000000" "replaced grid's cell size"
expect_clean grid
expect_clean .

# The output folder never holds an input: the input is neither removed nor replaced.
cp "$PBF" grid/city.osm.pbf
sum=$(sha1sum <grid/city.osm.pbf)
run_cmd gridify -q -overwrite -tr 24 grid/city.osm.pbf grid
expect_status 1
expect_stderr "ERROR: output folder 'grid' holds the input 'grid/city.osm.pbf'; write the output to another folder"
expect_eq "$(sha1sum <grid/city.osm.pbf)" "$sum" "input inside the output folder"
run_cmd gridify -q -overwrite -tr 24 grid/city.osm.pbf .
expect_status 1
expect_stderr "ERROR: output folder '.' holds the input 'grid/city.osm.pbf'; write the output to another folder"
expect_exists grid/notes.txt
rm grid/city.osm.pbf

# --- an output is never one of the inputs (same path, symlink, hard link) --------------------------
cp "$BUB/landuse.tif" "$BUB/density.tif" .
sum=$(sha1sum <landuse.tif)
ln -s landuse.tif soft.tif
ln landuse.tif hard.tif
for out in landuse.tif soft.tif hard.tif; do
  run_cmd vectorize -q -overwrite landuse.tif "$out"
  expect_status 1
  expect_stderr "ERROR: output file '$out' would replace the input 'landuse.tif'; choose another output name"
done
run_cmd vectorize -q -overwrite -density density.tif landuse.tif density.tif
expect_status 1
expect_stderr "ERROR: output file 'density.tif' would replace the input 'density.tif'; choose another output name"
expect_eq "$(sha1sum <landuse.tif)" "$sum" "input after refused runs"
expect_eq "$(readlink soft.tif)" "landuse.tif" "symlink input"
run_cmd shape-metrics -q -overwrite "$WORK/grid/truth.gpkg" "$WORK/grid/truth.gpkg"
expect_status 1
expect_stderr_contains "would replace the input"
run_cmd evaluate -q -overwrite -json "$WORK/grid/truth.gpkg" "$WORK/grid/truth.gpkg" "$WORK/grid/truth.gpkg"
expect_status 1
expect_stderr "ERROR: output file '$WORK/grid/truth.gpkg' would replace the input '$WORK/grid/truth.gpkg'; choose another output name"
run_cmd vectorize -q -debug-stages . landuse.tif stages.gpkg
expect_status 2
expect_stderr "ERROR: -debug-stages '.' would write stages.gpkg, which is the output 'stages.gpkg'; choose another folder or output name"

# --- multi-file formats: Shapefile -----------------------------------------------------------------
run_cmd vectorize -q -of "ESRI Shapefile" landuse.tif city.shp
expect_status 2
expect_stderr "ERROR: -of ESRI Shapefile holds one layer per file and 8 layers are written: give a folder name instead of 'city.shp' (each layer becomes <folder>/<layer>.shp)"
expect_missing city.shp
run_cmd vectorize -q landuse.tif city.gpkg
expect_status 0
run_cmd vectorize -q -of "ESRI Shapefile" landuse.tif city_shp
expect_status 0
expect_clean .
for layer in roads road_nodes pavement blocks water spines parcels; do
  expect_eq "$(feature_count city_shp "$layer")" "$(feature_count city.gpkg "$layer")" "Shapefile layer $layer"
  expect_exists "city_shp/$layer.prj"
done
expect_exists city_shp/vectorize_report.dbf
ogrinfo -ro -so city_shp/parcels.shp parcels | grep -q 'ETRS89\|Krovak\|PROJCRS' || fail "Shapefile parcels lost the CRS"
first=$(checksums city_shp)
# A second run to another name leaves the first run's files alone; to the same name it needs -overwrite.
run_cmd vectorize -q -of "ESRI Shapefile" -roads-only landuse.tif other_shp
expect_status 0
expect_eq "$(checksums city_shp)" "$first" "first Shapefile output after a run to another name"
run_cmd vectorize -q -of "ESRI Shapefile" -roads-only landuse.tif city_shp
expect_status 1
expect_stderr_contains "ERROR: output folder 'city_shp' already holds roads.shp, roads.shx, roads.dbf, roads.prj"
expect_eq "$(checksums city_shp)" "$first" "Shapefile output after a refused run"
# One layer in a Shapefile: the file set lands beside each other under the given name.
run_cmd shape-metrics -q "$WORK/city.gpkg" -layer blocks blocks.shp
expect_status 0
for ext in shp shx dbf prj; do expect_exists "blocks.$ext"; done
expect_eq "$(ogrinfo -ro -so blocks.shp blocks | sed -n 's/^Feature Count: //p')" "$(feature_count city.gpkg blocks)" "single-layer Shapefile"
expect_clean .

# -overwrite also removes the side files of the previous output that this run does not write: a
# boundary without -a_srs must not keep the .prj of one with it.
run_cmd boundary -q -size 64 -layers 2-6 -a_srs EPSG:32633 -cellsize 10 -center 500000 5000000 shape.shp
expect_status 0
expect_exists shape.prj
run_cmd boundary -q -size 64 -layers 2-6 -overwrite shape.shp
expect_status 0
expect_missing shape.prj
if ogrinfo -ro -so shape.shp boundary | grep -q 'UTM'; then fail "the pixel-unit boundary still claims a CRS"; fi
expect_clean .

# An output folder that is a symlink into another file system is written in place (staged inside it).
if [ -d /dev/shm ] && [ -w /dev/shm ]; then
  elsewhere=$(mktemp -d /dev/shm/urbanvec_test.XXXXXX)
  ln -s "$elsewhere" linked_grid
  run_cmd gridify -q -tr 30 "$PBF" linked_grid
  expect_status 0
  expect_exists "$elsewhere/truth.gpkg"
  expect_clean "$elsewhere"
  rm -rf "$elsewhere" linked_grid
fi

# --- format and creation options are checked before any work --------------------------------------
run_cmd vectorize -q -of Nonsense "$MON/landuse.tif" never.gpkg
expect_status 2
expect_stderr "ERROR: -of: 'Nonsense' is not a vector format GDAL can write"
run_cmd vectorize -q -lco SPATIAL_INDEX=MAYBE "$MON/landuse.tif" never.gpkg
expect_status 2
expect_stderr "ERROR: -lco SPATIAL_INDEX=MAYBE: SPATIAL_INDEX of GPKG takes YES or NO, got 'MAYBE'"
start=$(date +%s%N)
run_cmd vectorize -q -lco NO_SUCH_OPTION=1 "$MON/landuse.tif" never.gpkg
elapsed_ms=$((($(date +%s%N) - start) / 1000000))
expect_status 2
expect_stderr_contains "ERROR: -lco NO_SUCH_OPTION=1: GPKG has no layer creation option 'NO_SUCH_OPTION' (it takes "
# Monaco takes seconds to vectorize; a refusal before the work takes a fraction of that.
[ "$elapsed_ms" -lt 1500 ] || fail "the -lco check came after the work ($elapsed_ms ms)"
run_cmd vectorize -q -dsco VERSION=9.9 landuse.tif never.gpkg
expect_status 2
expect_stderr_contains "ERROR: -dsco VERSION=9.9: VERSION of GPKG takes one of AUTO, 1.0, 1.1, 1.2, 1.3"
expect_missing never.gpkg
run_cmd gridify -q -co TILED=MAYBE -tr 24 "$PBF" never_grid
expect_status 2
expect_stderr "ERROR: -co TILED=MAYBE: TILED of GTiff takes YES or NO, got 'MAYBE'"
expect_missing never_grid
expect_clean .

# --- two runs on one new name: the second is refused, the first's result stays ---------------------
URBANVEC_FAULT=write-delay-ms=400 "$URBANVEC" vectorize -q landuse.tif race.gpkg 2>race_a.err &
first_pid=$!
for _ in $(seq 50); do [ -e .race.gpkg.lock ] && break; sleep 0.05; done
run_cmd vectorize -q landuse.tif race.gpkg
expect_status 1
expect_stderr "ERROR: output file 'race.gpkg' is being written by another run (process $first_pid); wait for it to finish or choose another output name"
wait "$first_pid" || fail "the first run failed: $(cat race_a.err)"
expect_eq "$(feature_count race.gpkg parcels)" "$(feature_count city.gpkg parcels)" "first run's output"
expect_missing .race.gpkg.lock

# --- signals at each phase --------------------------------------------------------------------------
cp city.gpkg sig.gpkg
old=$(sha1sum <sig.gpkg)
# signal_when <URBANVEC_FAULT> <condition>: runs vectorize on Monaco into sig.gpkg with progress lines
# in sig.out, waits until the condition holds (the phase is reached; PID is the run), then SIGTERM.
signal_when() {
  set +e
  URBANVEC_FAULT="$1" "$URBANVEC" vectorize -progress lines -overwrite "$MON/landuse.tif" sig.gpkg >sig.out 2>sig.err &
  PID=$!
  local reached=no
  for _ in $(seq 1200); do
    if eval "$2"; then reached=yes; break; fi
    sleep 0.05
  done
  [ "$reached" = yes ] || fail "phase '$2' never reached"
  kill -TERM "$PID"
  wait "$PID"
  STATUS=$?
  ERR=$(grep -v '^Warning: [0-9]* closed boundar' sig.err || true)
  set -e
}
signal_when "" "grep -q '^PROGRESS' sig.out"  # while computing
expect_status 3
expect_stderr "ERROR: cancelled; no output was written"
grep -q ' writing$' sig.out && fail "the run computing when signalled had reached writing"
expect_eq "$(sha1sum <sig.gpkg)" "$old" "output after a cancel while computing"
signal_when write-delay-ms=1500 '[ -e ".sig.tmp-$PID.gpkg/sig.gpkg" ]'  # while writing the layers
expect_status 3
expect_stderr "ERROR: cancelled; no output was written"
expect_eq "$(sha1sum <sig.gpkg)" "$old" "output after a cancel while writing"
expect_clean .
signal_when commit-delay-ms=3000 "grep -q ' writing$' sig.out"  # past the point of no return
expect_status 0
expect_stderr "Warning: interrupted while the output was being moved into place; the run finished, and its output is complete"
[ "$(sha1sum <sig.gpkg)" != "$old" ] || fail "the output was not replaced after the point of no return"
[ "$(feature_count sig.gpkg roads)" -gt 700 ] || fail "the output after a late signal is not Monaco's (785 roads)"
old=$(sha1sum <sig.gpkg)
cp city.gpkg sig.gpkg
bub=$(sha1sum <sig.gpkg)
signal_when after-commit-delay-ms=3000 '[ "$(sha1sum <sig.gpkg)" != "$bub" ]'  # after the output is in place
expect_status 0
expect_stderr "Warning: interrupted while the output was being moved into place; the run finished, and its output is complete"
expect_eq "$(sha1sum <sig.gpkg)" "$old" "Monaco output after a signal once it was in place"
expect_clean .

# --- a killed run's temporaries are removed by the next run on that name ---------------------------
URBANVEC_FAULT=write-delay-ms=5000 "$URBANVEC" vectorize -q -overwrite landuse.tif sig.gpkg 2>/dev/null &
killed=$!
for _ in $(seq 100); do [ -e ".sig.tmp-$killed.gpkg" ] && break; sleep 0.05; done
sleep 0.3
kill -KILL "$killed"
wait "$killed" || true
expect_exists ".sig.tmp-$killed.gpkg"
mkdir ".sig.tmp-$$.gpkg"  # a live process's temporary: never touched
run_cmd vectorize -q -overwrite landuse.tif sig.gpkg
expect_status 0
expect_missing ".sig.tmp-$killed.gpkg"
expect_exists ".sig.tmp-$$.gpkg"
rmdir ".sig.tmp-$$.gpkg"
expect_missing .sig.gpkg.lock

# --- an injected write fault: exit 1, the old output kept, nothing left behind ---------------------
cp city.gpkg fault.gpkg
old=$(sha1sum <fault.gpkg)
export URBANVEC_FAULT=write-fail-after=25
run_cmd vectorize -q -overwrite landuse.tif fault.gpkg
expect_status 1
expect_stderr_contains "ERROR: cannot write a feature of layer 'roads' (fault injected by URBANVEC_FAULT)"
expect_eq "$(sha1sum <fault.gpkg)" "$old" "output after a failed write"
first=$(checksums city_shp)
run_cmd vectorize -q -overwrite -of "ESRI Shapefile" landuse.tif city_shp
expect_status 1
expect_eq "$(checksums city_shp)" "$first" "Shapefile folder after a failed write"
run_cmd gridify -q -overwrite -tr 30 "$PBF" grid
expect_status 1
expect_eq "$(checksums grid | grep -v -e landuse -e density -e parcels -e truth)" "$before" "gridify folder after a failed write"
expect_eq "$(gdalinfo grid/landuse.tif | sed -n 's/^Pixel Size = (\([0-9.]*\),.*/\1/p')" "30.000000000000000" "grid after a failed rerun"
unset URBANVEC_FAULT
expect_clean .
expect_clean grid

# --- the same input gives the same bytes, whatever the thread count or the time of the run ---------
run_cmd vectorize -q -threads 1 landuse.tif same1.gpkg
sleep 1.1  # GeoPackage stamps tables with the time of writing unless the writer fixes it
run_cmd vectorize -q -threads 2 landuse.tif same2.gpkg
expect_eq "$(sha1sum <same2.gpkg)" "$(sha1sum <same1.gpkg)" "bytes of two runs"

# --- usage errors exit 2, enum values in --help -----------------------------------------------------
run_cmd vectorize -tries -1 landuse.tif x.gpkg
expect_status 2
expect_stderr "ERROR: -tries must be at least 1, got -1"
run_cmd vectorize -spine-method nope landuse.tif x.gpkg
expect_status 2
run_cmd gridify -tr nan "$PBF" g2
expect_status 2
expect_stderr "ERROR: -tr expects a finite number, got 'nan'"
run_cmd vectorize --help
expect_stdout_contains "Values: gdal, lines, none."
printf '%s' "$OUT" | grep -A1 '^  -spine-method' | grep -q 'Values: ' || fail "-spine-method help lacks its values"

finish
