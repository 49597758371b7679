#include "urbanvec/io/gdal_types.hpp"

#include <cpl_conv.h>

namespace urbanvec::io {

LineString fromOgrCurve(const OGRSimpleCurve& curve) {
  LineString out(static_cast<size_t>(curve.getNumPoints()));
  for (int i = 0; i < curve.getNumPoints(); ++i) out[static_cast<size_t>(i)] = {curve.getX(i), curve.getY(i)};
  return out;
}

Polygon fromOgrPolygon(const OGRPolygon& polygon) {
  Polygon out;
  if (const OGRLinearRing* exterior = polygon.getExteriorRing()) out.outer = fromOgrCurve(*exterior);
  for (int i = 0; i < polygon.getNumInteriorRings(); ++i)
    out.holes.push_back(fromOgrCurve(*polygon.getInteriorRing(i)));
  return out;
}

std::string wktOf(const OGRSpatialReference& srs) {
  char* wkt = nullptr;
  const char* options[] = {"FORMAT=WKT2_2019", nullptr};
  srs.exportToWkt(&wkt, options);
  std::string out = wkt ? wkt : "";
  CPLFree(wkt);
  return out;
}

}  // namespace urbanvec::io
