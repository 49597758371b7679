// CRS handling with PROJ through OGRSpatialReference.
#pragma once

#include <string>

namespace urbanvec::io {

/// WKT of a CRS given as any string GDAL accepts (EPSG:32632, WKT, PROJ string, a file); throws an
/// InvalidOption error naming `option` when it is not understood.
std::string crsToWkt(const std::string& userCrs, const std::string& option);
bool isGeographic(const std::string& wkt);
/// True for a projected CRS whose linear unit is the metre.
bool isProjectedInMetres(const std::string& wkt);
/// Short human name: "EPSG:32632" when known, else the CRS name.
std::string crsShortName(const std::string& wkt);
/// Why a grid in CRS `wkt` cannot be measured in metres: "degrees" for a geographic CRS, the plural
/// of the linear unit ("US survey feet") for a projected CRS in another unit; empty for a projected
/// CRS in metres, no CRS, or one that cannot be read.
std::string nonMetricUnit(const std::string& wkt);
/// EPSG code of the WGS 84 / UTM zone containing the point (x, y) given in CRS `wkt` (in GDAL's
/// traditional x = easting/longitude order); 0 when the point cannot be brought to longitude/latitude.
int utmEpsgAt(const std::string& wkt, double x, double y);

}  // namespace urbanvec::io

namespace urbanvec::io {
/// True when two CRS (WKT) are the same (OGRSpatialReference::IsSame); two empty strings are the same.
bool sameCrs(const std::string& a, const std::string& b);
}  // namespace urbanvec::io
