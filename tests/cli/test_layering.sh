#!/usr/bin/env bash
# The dependency rule of docs/architecture.md (core <- io <- modules <- app <- cli) holds on src/, and
# the checker catches each kind of violation planted in a small tree.
set -euo pipefail
source "$(dirname "$0")/lib.sh"
CHECK="$URBANVEC_SOURCE_DIR/scripts/check_layering.py"

set +e
report=$(python3 "$CHECK")
status=$?
set -e
expect_eq "$status" "0" "layering of src/ ($report)"

plant() {  # plant <file under src> <line>
  mkdir -p "$WORK/src/$(dirname "$1")"
  printf '%s\n' "$2" >>"$WORK/src/$1"
}
plant urbanvec/core/a.hpp '#include "urbanvec/core/b.hpp"'
plant urbanvec/io/reader.cpp '#include "urbanvec/gridify/city_data.hpp"'
plant urbanvec/gridify/x.cpp '#include "urbanvec/io/raster_io.hpp"'
plant urbanvec/gridify/y.cpp '#include <gdal_priv.h>'
plant urbanvec/core/z.cpp '#include "urbanvec/app/command.hpp"'
plant urbanvec/streets/s.cpp '#include "urbanvec/shrink/t.hpp"'
plant urbanvec/shrink/t.cpp '#include "urbanvec/streets/s.hpp"'
plant urbanvec/app/ok.cpp '#include "urbanvec/gridify/city_data.hpp"'
plant cli/ok.cpp '#include <gdal_priv.h>'
set +e
python3 "$CHECK" "$WORK/src" >"$WORK/found.txt"
status=$?
set -e
expect_eq "$status" "1" "checker status on the planted tree"
cat >"$WORK/expected.txt" <<'TXT'
src/urbanvec/core/z.cpp:1: core includes urbanvec/app/command.hpp (app), against core <- io <- modules <- app <- cli
src/urbanvec/gridify/x.cpp:1: gridify includes urbanvec/io/raster_io.hpp (io), against core <- io <- modules <- app <- cli
src/urbanvec/gridify/y.cpp:1: gridify includes the GDAL/PROJ header <gdal_priv.h>; only io, app and the command may
src/urbanvec/io/reader.cpp:1: io includes urbanvec/gridify/city_data.hpp (module), against core <- io <- modules <- app <- cli
modules include each other in a cycle: shrink -> streets -> shrink
TXT
sort "$WORK/expected.txt" >"$WORK/expected.sorted"
sort "$WORK/found.txt" >"$WORK/found.sorted"
diff "$WORK/expected.sorted" "$WORK/found.sorted" >"$WORK/diff.txt" || fail "checker findings differ: $(cat "$WORK/diff.txt")"
finish
