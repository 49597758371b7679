#include "urbanvec/io/crs.hpp"

#include <cpl_conv.h>
#include <ogr_spatialref.h>

#include <cmath>

#include "urbanvec/core/error.hpp"
#include "urbanvec/io/gdal_init.hpp"

namespace urbanvec::io {

std::string crsToWkt(const std::string& userCrs, const std::string& option) {
  ensureGdal();
  OGRSpatialReference srs;
  if (userCrs.empty() || srs.SetFromUserInput(userCrs.c_str()) != OGRERR_NONE)
    throw invalidOption(option + ": cannot understand the CRS '" + userCrs + "'");
  char* wkt = nullptr;
  const char* opts[] = {"FORMAT=WKT2_2019", nullptr};
  srs.exportToWkt(&wkt, opts);
  std::string out = wkt ? wkt : "";
  CPLFree(wkt);
  return out;
}

bool isGeographic(const std::string& wkt) {
  OGRSpatialReference srs;
  return !wkt.empty() && srs.importFromWkt(wkt.c_str()) == OGRERR_NONE && srs.IsGeographic();
}

bool isProjectedInMetres(const std::string& wkt) {
  OGRSpatialReference srs;
  if (wkt.empty() || srs.importFromWkt(wkt.c_str()) != OGRERR_NONE || !srs.IsProjected()) return false;
  return std::fabs(srs.GetLinearUnits() - 1.0) < 1e-9;
}

std::string crsShortName(const std::string& wkt) {
  OGRSpatialReference srs;
  if (wkt.empty() || srs.importFromWkt(wkt.c_str()) != OGRERR_NONE) return "none";
  srs.AutoIdentifyEPSG();
  const char* auth = srs.GetAuthorityName(nullptr);
  const char* code = srs.GetAuthorityCode(nullptr);
  if (auth && code) return std::string(auth) + ":" + code;
  const char* name = srs.GetName();
  return name ? name : "unnamed";
}

}  // namespace urbanvec::io
