// GDAL/OGR objects as io and the app-layer adapters share them: an owning dataset pointer, OGR
// geometry to core geometry, and a CRS as WKT — one definition each, for every reader.
#pragma once

#include <gdal_priv.h>
#include <ogr_geometry.h>
#include <ogr_spatialref.h>

#include <memory>
#include <string>

#include "urbanvec/core/geometry.hpp"

namespace urbanvec::io {

struct DatasetCloser {
  void operator()(GDALDataset* ds) const { GDALClose(ds); }
};
/// A dataset closed when the pointer goes.
using DatasetPtr = std::unique_ptr<GDALDataset, DatasetCloser>;

/// The points of an OGR line or ring.
LineString fromOgrCurve(const OGRSimpleCurve& curve);
/// An OGR polygon with its holes.
Polygon fromOgrPolygon(const OGRPolygon& polygon);
/// The CRS as WKT2 (2019), "" when it cannot be exported.
std::string wktOf(const OGRSpatialReference& srs);

}  // namespace urbanvec::io
