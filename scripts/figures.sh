#!/usr/bin/env bash
# Remakes docs/figures/*.png from the sample grids: vectorize each sample city, then render the input
# grid beside the output headless with PyQGIS and the styles the GeoPackage carries.
# usage: scripts/figures.sh [urbanvec binary]
set -euo pipefail
cd "$(dirname "$0")/.."
URBANVEC=${1:-build/bin/urbanvec}
[ -x "$URBANVEC" ] || { echo "ERROR: '$URBANVEC' is not an executable urbanvec (build first: scripts/build.sh)" >&2; exit 1; }
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
mkdir -p docs/figures
for city in monaco bubenec; do
  G=sample_data/$city
  "$URBANVEC" vectorize -q -density "$G/density.tif" -parcels "$G/parcels.tif" -parcel-table "$G/parcels.csv" \
    "$G/landuse.tif" "$WORK/$city.gpkg"
  QT_QPA_PLATFORM=offscreen XDG_RUNTIME_DIR="$WORK" /usr/bin/python3 scripts/render_figures.py \
    "$G" "$WORK/$city.gpkg" "docs/figures/$city"
  echo "docs/figures/${city}_landuse.png docs/figures/${city}_density.png"
done
