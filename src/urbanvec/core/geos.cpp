#include "urbanvec/core/geos.hpp"

#include "urbanvec/core/error.hpp"

namespace urbanvec::geos {

namespace {
void onGeosError(const char* message, void* userdata) {
  *static_cast<std::string*>(userdata) = message ? message : "";
}

GEOSCoordSequence* sequence(GEOSContextHandle_t h, const std::vector<Vec2>& points, bool close) {
  const bool addClosing = close && !points.empty() && points.front() != points.back();
  const unsigned n = static_cast<unsigned>(points.size() + (addClosing ? 1 : 0));
  GEOSCoordSequence* seq = GEOSCoordSeq_create_r(h, n, 2);
  for (unsigned i = 0; i < points.size(); ++i) GEOSCoordSeq_setXY_r(h, seq, i, points[i].x, points[i].y);
  if (addClosing) GEOSCoordSeq_setXY_r(h, seq, n - 1, points.front().x, points.front().y);
  return seq;
}
}  // namespace

Context::Context() : handle_(GEOS_init_r()) {
  GEOSContext_setErrorMessageHandler_r(handle_, onGeosError, &lastError_);
}

Context::~Context() { GEOS_finish_r(handle_); }

GeomPtr Context::own(GEOSGeometry* g, const char* what) const {
  if (!g) throw internalError(std::string("GEOS failed in ") + what + (lastError_.empty() ? "" : ": " + lastError_));
  return GeomPtr(g, GeomDeleter{handle_});
}

GeomPtr Context::point(const Vec2& p) const { return own(GEOSGeom_createPointFromXY_r(handle_, p.x, p.y), "point"); }

bool Context::withinDistance(const GEOSPreparedGeometry* prepared, const GEOSGeometry* g,
                             double distance) const {
  double measured = 0.0;
  if (GEOSPreparedDistance_r(handle_, prepared, g, &measured) != 1)
    throw internalError("GEOS failed to measure a distance: " + lastError_);
  return measured <= distance;
}

GeomPtr Context::lineString(const LineString& line) const {
  return own(GEOSGeom_createLineString_r(handle_, sequence(handle_, line, false)), "lineString");
}

GeomPtr Context::polygon(const Polygon& polygon) const {
  GEOSGeometry* shell = GEOSGeom_createLinearRing_r(handle_, sequence(handle_, polygon.outer, true));
  if (!shell) throw internalError("GEOS failed to build a ring: " + lastError_);
  std::vector<GEOSGeometry*> holes;
  for (const Ring& r : polygon.holes) holes.push_back(GEOSGeom_createLinearRing_r(handle_, sequence(handle_, r, true)));
  return own(GEOSGeom_createPolygon_r(handle_, shell, holes.data(), static_cast<unsigned>(holes.size())), "polygon");
}

GeomPtr Context::collection(int type, std::vector<GeomPtr> parts) const {
  std::vector<GEOSGeometry*> raw;
  for (GeomPtr& p : parts) raw.push_back(p.release());
  return own(GEOSGeom_createCollection_r(handle_, type, raw.data(), static_cast<unsigned>(raw.size())), "collection");
}

GeomPtr Context::multiPolygon(const MultiPolygon& polygons) const {
  std::vector<GeomPtr> parts;
  for (const Polygon& p : polygons) parts.push_back(polygon(p));
  return collection(GEOS_MULTIPOLYGON, std::move(parts));
}

GeomPtr Context::multiLineString(const MultiLineString& lines) const {
  std::vector<GeomPtr> parts;
  for (const LineString& l : lines) parts.push_back(lineString(l));
  return collection(GEOS_MULTILINESTRING, std::move(parts));
}

LineString Context::coordinates(const GEOSGeometry* g) const {
  const GEOSCoordSequence* seq = GEOSGeom_getCoordSeq_r(handle_, g);
  unsigned n = 0;
  GEOSCoordSeq_getSize_r(handle_, seq, &n);
  LineString out(n);
  for (unsigned i = 0; i < n; ++i) GEOSCoordSeq_getXY_r(handle_, seq, i, &out[i].x, &out[i].y);
  return out;
}

MultiPolygon Context::toPolygons(const GEOSGeometry* g) const {
  MultiPolygon out;
  if (!g || GEOSisEmpty_r(handle_, g)) return out;
  const int type = GEOSGeomTypeId_r(handle_, g);
  if (type == GEOS_POLYGON) {
    Polygon p;
    p.outer = coordinates(GEOSGetExteriorRing_r(handle_, g));
    const int holes = GEOSGetNumInteriorRings_r(handle_, g);
    for (int i = 0; i < holes; ++i) p.holes.push_back(coordinates(GEOSGetInteriorRingN_r(handle_, g, i)));
    out.push_back(std::move(p));
  } else if (type == GEOS_MULTIPOLYGON || type == GEOS_GEOMETRYCOLLECTION) {
    const int n = GEOSGetNumGeometries_r(handle_, g);
    for (int i = 0; i < n; ++i) {
      MultiPolygon part = toPolygons(GEOSGetGeometryN_r(handle_, g, i));
      out.insert(out.end(), part.begin(), part.end());
    }
  }
  return out;
}

MultiLineString Context::toLines(const GEOSGeometry* g) const {
  MultiLineString out;
  if (!g || GEOSisEmpty_r(handle_, g)) return out;
  const int type = GEOSGeomTypeId_r(handle_, g);
  if (type == GEOS_LINESTRING || type == GEOS_LINEARRING) {
    out.push_back(coordinates(g));
  } else if (type == GEOS_MULTILINESTRING || type == GEOS_GEOMETRYCOLLECTION) {
    const int n = GEOSGetNumGeometries_r(handle_, g);
    for (int i = 0; i < n; ++i) {
      MultiLineString part = toLines(GEOSGetGeometryN_r(handle_, g, i));
      out.insert(out.end(), part.begin(), part.end());
    }
  }
  return out;
}

PreparedGeometries::PreparedGeometries(const Context& context, std::vector<const GEOSGeometry*> geometries)
    : context_(context), geometries_(std::move(geometries)), prepared_(geometries_.size(), nullptr) {}

PreparedGeometries::~PreparedGeometries() {
  for (const GEOSPreparedGeometry* p : prepared_)
    if (p) GEOSPreparedGeom_destroy_r(context_.handle(), p);
}

const GEOSPreparedGeometry* PreparedGeometries::operator[](std::size_t i) {
  if (!prepared_[i]) {
    prepared_[i] = GEOSPrepare_r(context_.handle(), geometries_[i]);
    if (!prepared_[i]) throw internalError("GEOS failed to prepare a geometry: " + context_.lastError());
  }
  return prepared_[i];
}

}  // namespace urbanvec::geos
