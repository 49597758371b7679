#pragma once

namespace urbanvec {
/// EPSG code of the WGS 84 / UTM zone containing (lon, lat) in degrees: 326zz north, 327zz south,
/// with the Norway and Svalbard exceptions.
int utmEpsgFor(double longitude, double latitude);
}  // namespace urbanvec
