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

}  // namespace urbanvec::io
