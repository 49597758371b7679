#!/usr/bin/env bash
# Builds the QGIS plugin zip a user installs with Plugins > Manage and Install Plugins > Install from ZIP.
# Usage: scripts/package-plugin.sh [output_dir]   (default: build/dist/)  Prints the path of the zip.
# The zip holds one top-level folder, urbanvec/, as QGIS's plugin manager expects; the version comes
# from plugin/urbanvec/metadata.txt. The urbanvec program itself is installed separately.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
out_dir="${1:-$root/build/dist}"
plugin="$root/plugin/urbanvec"
[ -f "$plugin/metadata.txt" ] || { echo "ERROR: $plugin/metadata.txt not found" >&2; exit 1; }
version="$(sed -n 's/^version=//p' "$plugin/metadata.txt" | head -n1)"
[ -n "$version" ] || { echo "ERROR: no version= line in $plugin/metadata.txt" >&2; exit 1; }
mkdir -p "$out_dir"
out_dir="$(cd "$out_dir" && pwd)"
zip_path="$out_dir/urbanvec-qgis-plugin-$version.zip"
stage="$(mktemp -d)"
trap 'rm -rf "$stage"' EXIT
# Only what the plugin needs: sources, metadata, icon, styles (no caches, no editor files).
(cd "$root/plugin" && find urbanvec -type f \( -name '*.py' -o -name 'metadata.txt' -o -name '*.svg' \
  -o -name '*.qml' -o -name '*.md' \) -not -path '*/__pycache__/*' | LC_ALL=C sort) > "$stage/files"
rm -f "$zip_path.tmp"
(cd "$root/plugin" && zip -q -X "$zip_path.tmp" -@ < "$stage/files")
mv "$zip_path.tmp" "$zip_path"
echo "$zip_path"
