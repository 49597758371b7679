"""urbanvec-tiles: `urbanvec vectorize` in tiles with a halo, on Dask distributed (issue 22).

Modules: plan (tile layout), tile (one tile: run `urbanvec vectorize -srcwin`, keep what the tile
owns, halo guard), stitch (merge the tiles into one GeoPackage), digest (canonical comparison),
cli (the `urbanvec-tiles` command). docs/scale.md describes the design.
"""
