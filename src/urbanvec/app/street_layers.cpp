// Reading the vector inputs of the streets commands (see the header).
#include "urbanvec/app/street_layers.hpp"

#include <limits>

#include "urbanvec/core/error.hpp"
#include "urbanvec/io/crs.hpp"
#include "urbanvec/io/vector_io.hpp"

namespace urbanvec::app {
namespace {

void extendBox(const Geometry& g, double& minX, double& minY, double& maxX, double& maxY) {
  auto add = [&](const Vec2& p) {
    minX = std::min(minX, p.x), maxX = std::max(maxX, p.x);
    minY = std::min(minY, p.y), maxY = std::max(maxY, p.y);
  };
  auto ring = [&](const std::vector<Vec2>& r) {
    for (const Vec2& p : r) add(p);
  };
  if (const auto* p = std::get_if<Vec2>(&g)) add(*p);
  if (const auto* l = std::get_if<LineString>(&g)) ring(*l);
  if (const auto* ml = std::get_if<MultiLineString>(&g))
    for (const LineString& l : *ml) ring(l);
  if (const auto* p = std::get_if<Polygon>(&g)) ring(p->outer);
  if (const auto* mp = std::get_if<MultiPolygon>(&g))
    for (const Polygon& p : *mp) ring(p.outer);
}

bool undefinedCrs(const std::string& wkt) {
  // GeoPackage stores "no CRS" as srs_id 0/-1, read back as "Undefined geographic/cartesian SRS".
  return wkt.empty() || io::crsShortName(wkt).rfind("Undefined", 0) == 0;
}

}  // namespace

LoadedLayer readLayer(const LayerRequest& request, const std::string& targetCrsWkt, bool toUtm) {
  std::string name = request.layer;
  if (name.empty()) {
    const std::vector<std::string> layers = io::listVectorLayers(request.path, request.role);
    if (layers.empty()) throw invalidInput(request.role + " '" + request.path + "' has no vector layer");
    name = layers.front();
  }
  io::VectorReadOptions read;
  read.where = request.where;
  std::optional<io::LayerRead> loaded = io::readVectorLayer(request.path, name, request.role, read);
  if (!loaded) throw invalidInput(request.role + " '" + request.path + "' has no layer '" + name + "'");
  std::string crs = undefinedCrs(loaded->crsWkt) ? std::string() : loaded->crsWkt;
  std::string target = targetCrsWkt;
  if (target.empty() && toUtm && !crs.empty() && io::isGeographic(crs)) {
    double minX = std::numeric_limits<double>::infinity(), minY = minX, maxX = -minX, maxY = -minX;
    for (const Feature& f : loaded->layer.features) extendBox(f.geometry, minX, minY, maxX, maxY);
    if (minX <= maxX) {
      const int epsg = io::utmEpsgAt(crs, (minX + maxX) / 2, (minY + maxY) / 2);
      if (epsg > 0) target = io::crsToWkt("EPSG:" + std::to_string(epsg), request.role);
    }
  }
  if (!target.empty() && !crs.empty() && !io::sameCrs(crs, target)) {
    read.targetCrs = target;
    loaded = io::readVectorLayer(request.path, name, request.role, read);
    crs = target;
  } else if (!target.empty() && crs.empty()) {
    throw invalidInput(request.role + " '" + request.path + "' (layer '" + name +
                       "') has no CRS, so it cannot be brought into " + io::crsShortName(target) +
                       "; assign one (ogr2ogr -a_srs)");
  }
  LoadedLayer out;
  out.layer = std::move(loaded->layer);
  out.crsWkt = crs;
  return out;
}

std::vector<LineString> linesOf(const Layer& layer) {
  std::vector<LineString> lines;
  auto add = [&](const LineString& l) {
    if (l.size() >= 2) lines.push_back(l);
  };
  for (const Feature& f : layer.features) {
    if (const auto* l = std::get_if<LineString>(&f.geometry)) add(*l);
    if (const auto* ml = std::get_if<MultiLineString>(&f.geometry))
      for (const LineString& l : *ml) add(l);
    if (const auto* p = std::get_if<Polygon>(&f.geometry)) {
      add(p->outer);
      for (const Ring& h : p->holes) add(h);
    }
    if (const auto* mp = std::get_if<MultiPolygon>(&f.geometry))
      for (const Polygon& p : *mp) {
        add(p.outer);
        for (const Ring& h : p.holes) add(h);
      }
  }
  return lines;
}

MultiPolygon polygonsOf(const Layer& layer, const std::string& role) {
  MultiPolygon polygons;
  for (const Feature& f : layer.features) {
    if (const auto* p = std::get_if<Polygon>(&f.geometry))
      if (p->outer.size() >= 4) polygons.push_back(*p);
    if (const auto* mp = std::get_if<MultiPolygon>(&f.geometry))
      for (const Polygon& p : *mp)
        if (p.outer.size() >= 4) polygons.push_back(p);
  }
  if (polygons.empty())
    throw invalidInput(role + ": layer '" + layer.name + "' holds no polygon (it must be a polygon layer)");
  return polygons;
}

}  // namespace urbanvec::app
