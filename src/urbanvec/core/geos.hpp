// A thin RAII layer over GEOS's reentrant C API, and conversions between GEOS and core geometry.
// Every module that needs robust planar operations (noding, polygonize, overlay, distances) uses this
// rather than its own wrapper. One GeosContext per thread.
#pragma once

#include <geos_c.h>

#include <memory>
#include <string>
#include <vector>

#include "urbanvec/core/geometry.hpp"

namespace urbanvec::geos {

class Context;

/// Owning pointer to a GEOS geometry, destroyed with the context that made it.
struct GeomDeleter {
  GEOSContextHandle_t handle = nullptr;
  void operator()(GEOSGeometry* g) const {
    if (g) GEOSGeom_destroy_r(handle, g);
  }
};
using GeomPtr = std::unique_ptr<GEOSGeometry, GeomDeleter>;

class Context {
 public:
  Context();
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  GEOSContextHandle_t handle() const { return handle_; }
  /// Takes ownership of a raw result; throws urbanvec::Error (Internal) naming `what` when it is null.
  GeomPtr own(GEOSGeometry* g, const char* what) const;

  GeomPtr point(const Vec2& p) const;
  GeomPtr lineString(const LineString& line) const;
  GeomPtr polygon(const Polygon& polygon) const;
  GeomPtr multiPolygon(const MultiPolygon& polygons) const;
  GeomPtr multiLineString(const MultiLineString& lines) const;
  /// A collection taking ownership of the parts (GEOS_GEOMETRYCOLLECTION, GEOS_MULTIPOLYGON, ...).
  GeomPtr collection(int type, std::vector<GeomPtr> parts) const;

  /// Polygonal parts of any geometry (Polygon, MultiPolygon, or collections of them).
  MultiPolygon toPolygons(const GEOSGeometry* g) const;
  /// Linear parts of any geometry.
  MultiLineString toLines(const GEOSGeometry* g) const;
  LineString coordinates(const GEOSGeometry* lineOrRing) const;

  /// Whether `g` is within `distance` of the prepared geometry (at distance 0 when one holds a point of
  /// the other): GEOSPreparedDistanceWithin's answer, but for a prepared polygon or line GEOS 3.11
  /// answers that one by DistanceOp over every pair of segments, while the prepared distance indexes the
  /// prepared geometry's segments (IndexedFacetDistance) and finds the same minimum.
  bool withinDistance(const GEOSPreparedGeometry* prepared, const GEOSGeometry* g, double distance) const;

  /// Last error GEOS reported on this context.
  const std::string& lastError() const { return lastError_; }

 private:
  GEOSContextHandle_t handle_;
  std::string lastError_;
};

/// Prepared (indexed) forms of geometries that the caller keeps alive, made on first use: repeated
/// predicates and distances against a large geometry then cost O(log n) instead of O(n). Not thread
/// safe; one per context.
class PreparedGeometries {
 public:
  PreparedGeometries(const Context& context, std::vector<const GEOSGeometry*> geometries);
  ~PreparedGeometries();
  PreparedGeometries(const PreparedGeometries&) = delete;
  PreparedGeometries& operator=(const PreparedGeometries&) = delete;
  /// The prepared form of geometry i; throws urbanvec::Error (Internal) when GEOS cannot prepare it.
  const GEOSPreparedGeometry* operator[](std::size_t i);

 private:
  const Context& context_;
  std::vector<const GEOSGeometry*> geometries_;
  std::vector<const GEOSPreparedGeometry*> prepared_;
};

}  // namespace urbanvec::geos
