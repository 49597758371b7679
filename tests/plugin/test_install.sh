#!/usr/bin/env bash
# The two ways users install the plugin: `cmake --install` (plugin + program under one prefix; the
# plugin finds the program there without PATH) and the zip from scripts/package-plugin.sh, unpacked
# into the profile's plugin folder as QGIS's plugin manager does.
set -euo pipefail
source "$(dirname "$0")/qgis_env.sh"
: "${URBANVEC_BUILD_DIR:?set URBANVEC_BUILD_DIR to the build folder}"
export PYTHONPATH=  # QGIS must import the installed copies of the plugin, not the sources
qp() { qgis_process.bin "$@" 2> >(grep -v -e 'setapi() is deprecated' -e '^$' >&2); }
program_dir="$(dirname "$URBANVEC")"
export PATH="$(echo "$PATH" | tr ':' '\n' | grep -vx "$program_dir" | paste -sd: -)"
command -v urbanvec >/dev/null && fail "an urbanvec program is on PATH: $(command -v urbanvec)"

# 1. cmake --install into a prefix.
prefix="$WORK/prefix"
cmake --install "$URBANVEC_BUILD_DIR" --prefix "$prefix" > "$WORK/install.log"
plugins="$prefix/share/qgis/python/plugins"
for f in urbanvec/__init__.py urbanvec/metadata.txt urbanvec/provider.py urbanvec/styles/parcels.qml urbanvec/icon.svg; do
  [ -f "$plugins/$f" ] || fail "cmake --install did not install $f"
done
[ -x "$prefix/bin/urbanvec" ] || fail "cmake --install did not install bin/urbanvec"
[ -z "$(find "$plugins/urbanvec" -name __pycache__)" ] || fail "cmake --install copied __pycache__"
QGIS_PLUGINPATH="$plugins" qp list > "$WORK/list.txt"
grep -q 'urbanvec:vectorize' "$WORK/list.txt" || fail "the installed plugin did not find the installed program"
"$QGIS_PYTHON" -c "
import sys; sys.path.insert(0, '$PLUGIN_TESTS')
src = open('$PLUGIN_TESTS/qgis_start.py').read()
ns = {}; exec(src.replace('from qgis.core import QgsApplication', ''), ns); ns['make_inputs']('$WORK')"
QGIS_PLUGINPATH="$plugins" qp run urbanvec:gridify -- INPUT="$WORK/two.gpkg" TR=10 OUTPUT_DIR="$WORK/grid" > "$WORK/run.txt" \
  || { cat "$WORK/run.txt"; fail "gridify through the installed plugin failed"; }
grep -q "^$prefix/bin/urbanvec gridify -progress lines -tr 10 -overwrite " "$WORK/run.txt" \
  || fail "the installed program was not the one run: $(grep -m1 'gridify -progress' "$WORK/run.txt")"
[ -f "$WORK/grid/landuse.tif" ] || fail "no landuse.tif from the installed plugin"
echo "cmake --install: plugin in $plugins runs $prefix/bin/urbanvec"

# 2. The zip, installed as the plugin manager does it (unpacked into the profile's plugin folder).
zip_path="$(bash "$URBANVEC_SOURCE_DIR/scripts/package-plugin.sh" "$WORK/dist")"
[ -f "$zip_path" ] || fail "package-plugin.sh made no zip"
version="$(sed -n 's/^version=//p' "$URBANVEC_SOURCE_DIR/plugin/urbanvec/metadata.txt")"
[ "$(basename "$zip_path")" = "urbanvec-qgis-plugin-$version.zip" ] || fail "unexpected zip name $zip_path"
unzip -Z1 "$zip_path" > "$WORK/zip.txt"
grep -qvx 'urbanvec/.*' "$WORK/zip.txt" && fail "the zip has entries outside urbanvec/: $(grep -vx 'urbanvec/.*' "$WORK/zip.txt" | head -3)"
for f in urbanvec/__init__.py urbanvec/metadata.txt urbanvec/algorithm.py urbanvec/styles/parcels.qml; do
  grep -qx "$f" "$WORK/zip.txt" || fail "the zip lacks $f"
done
grep -q '__pycache__\|\.pyc$' "$WORK/zip.txt" && fail "the zip holds Python caches"
unzip -p "$zip_path" urbanvec/metadata.txt | grep -qx 'hasProcessingProvider=yes' || fail "metadata.txt does not declare the provider"
profile_plugins="$HOME/.local/share/QGIS/QGIS3/profiles/default/python/plugins"
mkdir -p "$profile_plugins"
unzip -q "$zip_path" -d "$profile_plugins"
unset QGIS_PLUGINPATH
PATH="$program_dir:$PATH" qp list > "$WORK/list2.txt"
grep -q 'urbanvec:vectorize' "$WORK/list2.txt" || fail "the plugin installed from the zip is not loaded"
echo "zip: $(basename "$zip_path"), $(wc -l < "$WORK/zip.txt") files, loads from the profile's plugin folder"
echo "PASS"
