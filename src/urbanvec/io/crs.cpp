#include "urbanvec/io/crs.hpp"

#include <cpl_conv.h>
#include <ogr_spatialref.h>

#include <cmath>
#include <memory>

#include "urbanvec/core/error.hpp"
#include "urbanvec/core/utm.hpp"
#include "urbanvec/io/gdal_init.hpp"
#include "urbanvec/io/gdal_types.hpp"

namespace urbanvec::io {

std::string crsToWkt(const std::string& userCrs, const std::string& option) {
  ensureGdal();
  OGRSpatialReference srs;
  if (userCrs.empty() || srs.SetFromUserInput(userCrs.c_str()) != OGRERR_NONE)
    throw invalidOption(option + ": cannot understand the CRS '" + userCrs + "'");
  return wktOf(srs);
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

std::string nonMetricUnit(const std::string& wkt) {
  OGRSpatialReference srs;
  if (wkt.empty() || srs.importFromWkt(wkt.c_str()) != OGRERR_NONE) return "";
  if (srs.IsGeographic()) return "degrees";
  if (!srs.IsProjected()) return "";
  const char* name = nullptr;
  const double toMetres = srs.GetLinearUnits(&name);
  if (std::fabs(toMetres - 1.0) < 1e-9) return "";
  std::string unit = name && *name ? name : "units of " + std::to_string(toMetres) + " m";
  const std::string foot = "foot";
  if (unit.size() >= foot.size() && unit.compare(unit.size() - foot.size(), foot.size(), foot) == 0)
    unit.replace(unit.size() - foot.size(), foot.size(), "feet");
  else if (unit.rfind("units of ", 0) != 0 && unit.back() != 's')
    unit += "s";
  return unit;
}

int utmEpsgAt(const std::string& wkt, double x, double y) {
  ensureGdal();
  OGRSpatialReference srs;
  if (wkt.empty() || srs.importFromWkt(wkt.c_str()) != OGRERR_NONE) return 0;
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  OGRSpatialReference wgs84;
  wgs84.SetWellKnownGeogCS("WGS84");
  wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<OGRCoordinateTransformation, void (*)(OGRCoordinateTransformation*)> toLonLat(
      OGRCreateCoordinateTransformation(&srs, &wgs84), OGRCoordinateTransformation::DestroyCT);
  if (!toLonLat || !toLonLat->Transform(1, &x, &y) || !std::isfinite(x) || !std::isfinite(y)) return 0;
  return utmEpsgFor(x, y);
}

}  // namespace urbanvec::io

namespace urbanvec::io {
bool sameCrs(const std::string& a, const std::string& b) {
  if (a.empty() || b.empty()) return a.empty() && b.empty();
  ensureGdal();
  OGRSpatialReference sa, sb;
  if (sa.importFromWkt(a.c_str()) != OGRERR_NONE || sb.importFromWkt(b.c_str()) != OGRERR_NONE) return a == b;
  return sa.IsSame(&sb);
}
}  // namespace urbanvec::io
