// Inputs of the shrinking pipeline (spec §B.1): OSM through libosmium, importance from .osmi or OGR.
#include "urbanvec/app/shrink_source.hpp"

#include <ogr_spatialref.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <unordered_map>

#include "urbanvec/app/city_source.hpp"
#include "urbanvec/core/error.hpp"
#include "urbanvec/io/crs.hpp"
#include "urbanvec/io/gdal_init.hpp"
#include "urbanvec/io/osm_reader.hpp"
#include "urbanvec/io/osmi_reader.hpp"
#include "urbanvec/io/vector_io.hpp"

namespace urbanvec::app {
namespace {

using shrink::City;
using shrink::Place;

struct Builder {
  const io::OsmData& osm;
  City& city;
  OGRCoordinateTransformation* transform;
  std::unordered_map<std::int64_t, int> index;
  std::int64_t nextSynthetic = -1;

  /// City node of an OSM node id, or -1 when the file does not hold it.
  int node(std::int64_t id) {
    auto it = index.find(id);
    if (it != index.end()) return it->second;
    const io::OsmNode* n = osm.node(id);
    if (!n) return -1;
    double x = n->lon, y = n->lat;
    if (transform && !transform->Transform(1, &x, &y))
      throw invalidInput("OSM node " + std::to_string(id) + " cannot be projected");
    shrink::CityNode c;
    c.osmId = id;
    c.p = {x, y};
    c.inBounds = !osm.hasBounds || (n->lon >= osm.minLon && n->lon <= osm.maxLon && n->lat >= osm.minLat &&
                                    n->lat <= osm.maxLat);
    city.nodes.push_back(c);
    const int k = static_cast<int>(city.nodes.size()) - 1;
    index.emplace(id, k);
    return k;
  }
  int synthetic(const Vec2& p) {
    city.nodes.push_back({nextSynthetic--, p, true});
    return static_cast<int>(city.nodes.size()) - 1;
  }
  /// The nodes of a way present in the file.
  std::vector<int> wayNodes(const io::OsmWay& way) {
    std::vector<int> out;
    for (std::int64_t r : way.refs) {
      const int n = node(r);
      if (n >= 0) out.push_back(n);
    }
    return out;
  }
};

std::string numberText(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.10g", v);
  return buffer;
}

double unitValue(const std::string& text, bool& ok) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  ok = end != text.c_str() && *end == '\0' && std::isfinite(v);
  return v;
}

/// The ring of a bounding place: members n1, w1, n2, w2, ..., nn, wn, n1; each wi contributes its part
/// between ni and ni+1 (§B.1.2).
std::vector<int> boundingRing(Builder& b, const io::OsmiPlace& place, const std::string& path) {
  std::vector<int> ring;
  const auto& m = place.members;
  auto where = [&] {
    return "importance file '" + path + "' line " + std::to_string(place.line) + ": bounding place '" +
           place.id + "'";
  };
  for (size_t i = 0; i + 1 < m.size(); i += 2) {
    if (m[i].type != 'n' || m[i + 1].type != 'w' || i + 2 >= m.size() || m[i + 2].type != 'n')
      throw invalidInput(where() +
                         " must list members node, way, node, way, ..., node (the first node again)");
    const io::OsmWay* way = b.osm.way(m[i + 1].ref);
    if (!way) return {};
    auto find = [&](std::int64_t id) {
      for (size_t k = 0; k < way->refs.size(); ++k)
        if (way->refs[k] == id) return static_cast<long>(k);
      return -1L;
    };
    const long from = find(m[i].ref), to = find(m[i + 2].ref);
    if (from < 0 || to < 0)
      throw invalidInput(where() + ": node " + std::to_string(from < 0 ? m[i].ref : m[i + 2].ref) +
                         " is not on way " + std::to_string(way->id));
    const long step = from <= to ? 1 : -1;
    for (long k = from; k != to + step; k += step) {
      const int n = b.node(way->refs[static_cast<size_t>(k)]);
      if (n >= 0 && (ring.empty() || ring.back() != n)) ring.push_back(n);
    }
  }
  if (ring.size() < 3 || ring.front() != ring.back())
    throw invalidInput(where() + " does not close: its last member must be its first node");
  return ring;
}

void readOsmi(Builder& b, const std::string& path, std::vector<Place>& places, int& missing,
              std::vector<std::string>& missingExamples) {
  const io::OsmiFile file = io::readOsmiFile(path);
  for (const io::OsmiPlace& p : file.places) {
    const std::string where =
        "importance file '" + path + "' line " + std::to_string(p.line) + ": place '" + p.id + "'";
    Place place;
    place.id = p.id;
    if (const std::string* name = p.tag("name")) place.name = *name;
    const std::string* appear = p.tag("appearW");
    if (!appear) throw invalidInput(where + " has no appearW tag (mandatory, 0..1)");
    bool ok = false;
    place.appearW = unitValue(*appear, ok);
    if (!ok) throw invalidInput(where + " has appearW '" + *appear + "', not a number");
    if (place.appearW < 0.0 || place.appearW > 1.0)
      throw invalidInput(where + " has appearW " + *appear + ", outside 0..1");
    const std::string* function = p.tag("function");
    const bool bounding = function && (*function == "bounding" || *function == "boundary");
    auto noteMissing = [&](char type, std::int64_t ref) {
      ++missing;
      if (missingExamples.size() < 5)
        missingExamples.push_back(std::string(type == 'n'   ? "node "
                                              : type == 'w' ? "way "
                                                            : "relation ") +
                                  std::to_string(ref));
    };
    auto addWay = [&](const io::OsmWay& way) {
      if (place.osmId == 0) place.osmId = way.id;
      if (!way.highway.empty()) {
        place.streetIds.push_back(way.id);
        return;
      }
      std::vector<int> nodes = b.wayNodes(way);
      if (nodes.empty()) return;
      place.shapes.push_back(std::move(nodes));
      place.shapeIds.push_back(way.id);
    };
    if (bounding) {
      for (const io::OsmiMember& m : p.members)
        if ((m.type == 'n' && !b.osm.node(m.ref)) || (m.type == 'w' && !b.osm.way(m.ref)))
          noteMissing(m.type, m.ref);
      place.boundingRing = boundingRing(b, p, path);
      if (!p.members.empty()) place.osmId = p.members.front().ref;
      for (const io::OsmiMember& m : p.members)
        if (m.type == 'w')
          if (const io::OsmWay* way = b.osm.way(m.ref); way && !way->highway.empty())
            place.streetIds.push_back(way->id);
    } else {
      for (const io::OsmiMember& m : p.members) {
        if (m.type == 'n') {
          const int n = b.node(m.ref);
          if (n < 0) {
            noteMissing('n', m.ref);
            continue;
          }
          if (place.osmId == 0) place.osmId = m.ref;
          place.shapes.push_back({n});
          place.shapeIds.push_back(m.ref);
        } else if (m.type == 'w') {
          const io::OsmWay* way = b.osm.way(m.ref);
          if (!way) {
            noteMissing('w', m.ref);
            continue;
          }
          addWay(*way);
        } else {
          const io::OsmRelation* rel = b.osm.relation(m.ref);
          if (!rel) {
            noteMissing('r', m.ref);
            continue;
          }
          if (place.osmId == 0) place.osmId = rel->id;
          if (place.name.empty()) place.name = rel->name;
          for (const io::OsmMember& rm : rel->members)
            if (rm.type == 'w')
              if (const io::OsmWay* way = b.osm.way(rm.ref)) addWay(*way);
        }
      }
    }
    if (place.streetIds.empty() && place.shapes.empty() && place.boundingRing.empty()) continue;
    places.push_back(std::move(place));
  }
}

/// Importance drawn in QGIS: every feature of the layer(s) with an importance field is a place.
void readImportanceLayers(Builder& b, const std::string& path, const ShrinkSourceOptions& options,
                          const std::string& crsWkt, std::vector<Place>& places) {
  std::vector<std::string> layers;
  if (!options.importanceLayer.empty())
    layers.push_back(options.importanceLayer);
  else
    layers = io::listVectorLayers(path, "importance file");
  io::VectorReadOptions read;
  read.targetCrs = crsWkt;
  int usable = 0;
  for (const std::string& name : layers) {
    std::optional<io::LayerRead> loaded = io::readVectorLayer(path, name, "importance file", read);
    if (!loaded) throw invalidInput("importance file '" + path + "' has no layer '" + name + "'");
    const Layer& layer = loaded->layer;
    const int field = layer.fieldIndex(options.importanceField);
    if (field < 0) {
      if (!options.importanceLayer.empty())
        throw invalidInput("layer '" + name + "' of importance file '" + path + "' has no '" +
                           options.importanceField + "' field");
      continue;
    }
    ++usable;
    const int nameField = layer.fieldIndex("name"), functionField = layer.fieldIndex("function");
    for (size_t f = 0; f < layer.features.size(); ++f) {
      const Feature& feature = layer.features[f];
      const std::string where =
          "importance file '" + path + "' layer '" + name + "' feature " + std::to_string(f + 1);
      const FieldValue& v = feature.values[static_cast<size_t>(field)];
      double w = 0.0;
      if (const double* d = std::get_if<double>(&v))
        w = *d;
      else if (const std::int64_t* i = std::get_if<std::int64_t>(&v))
        w = static_cast<double>(*i);
      else if (const std::string* s = std::get_if<std::string>(&v)) {
        bool ok = false;
        w = unitValue(*s, ok);
        if (!ok) throw invalidInput(where + ": " + options.importanceField + " '" + *s + "' is not a number");
      } else {
        throw invalidInput(where + ": " + options.importanceField + " is empty");
      }
      if (!(w >= 0.0 && w <= 1.0))
        throw invalidInput(where + ": " + options.importanceField + " " + numberText(w) + " is outside 0..1");
      Place place;
      place.id = name + ":" + std::to_string(f + 1);
      place.appearW = w;
      if (nameField >= 0)
        if (const std::string* s = std::get_if<std::string>(&feature.values[static_cast<size_t>(nameField)]))
          place.name = *s;
      bool bounding = false;
      if (functionField >= 0)
        if (const std::string* s =
                std::get_if<std::string>(&feature.values[static_cast<size_t>(functionField)]))
          bounding = *s == "bounding" || *s == "boundary";
      auto addLine = [&](const std::vector<Vec2>& pts, bool closed) {
        std::vector<int> nodes;
        for (const Vec2& p : pts) nodes.push_back(b.synthetic(p));
        if (closed && nodes.size() >= 3) {
          if (pts.front() == pts.back())
            nodes.back() = nodes.front();
          else
            nodes.push_back(nodes.front());
        }
        if (bounding && closed)
          place.boundingRing = nodes;
        else {
          place.shapes.push_back(std::move(nodes));
          place.shapeIds.push_back(0);
        }
      };
      const Geometry& g = feature.geometry;
      if (const Vec2* p = std::get_if<Vec2>(&g))
        addLine({*p}, false);
      else if (const LineString* l = std::get_if<LineString>(&g))
        addLine(*l, false);
      else if (const MultiLineString* ml = std::get_if<MultiLineString>(&g))
        for (const auto& l2 : *ml) addLine(l2, false);
      else if (const Polygon* poly = std::get_if<Polygon>(&g))
        addLine(poly->outer, true);
      else if (const MultiPolygon* mp = std::get_if<MultiPolygon>(&g))
        for (const auto& p2 : *mp) addLine(p2.outer, true);
      if (place.shapes.empty() && place.boundingRing.empty()) continue;
      places.push_back(std::move(place));
    }
  }
  if (usable == 0)
    throw invalidInput("importance file '" + path +
                       "' is neither an .osmi file nor a vector dataset with an '" + options.importanceField +
                       "' field");
}

}  // namespace

ShrinkSource readShrinkSource(const std::string& osmPath, const std::string& importancePath,
                              const ShrinkSourceOptions& options,
                              const std::function<void(const std::string&)>& warn) {
  io::ensureGdal();
  const io::OsmData osm = io::readOsmFile(osmPath, "OSM file");
  if (osm.nodes.empty()) throw invalidInput("OSM file '" + osmPath + "' holds no node");
  double cLon, cLat;
  if (osm.hasBounds) {
    cLon = (osm.minLon + osm.maxLon) / 2, cLat = (osm.minLat + osm.maxLat) / 2;
  } else {
    double a = 1e300, bb = 1e300, c = -1e300, d = -1e300;
    for (const io::OsmNode& n : osm.nodes)
      a = std::min(a, n.lon), c = std::max(c, n.lon), bb = std::min(bb, n.lat), d = std::max(d, n.lat);
    cLon = (a + c) / 2, cLat = (bb + d) / 2;
  }
  ShrinkSource source;
  const std::string wgs84 = io::crsToWkt("EPSG:4326", "OSM CRS");
  source.crsWkt = chooseGridCrs(wgs84, cLon, cLat, options.targetCrs);
  OGRSpatialReference from, to;
  from.importFromWkt(wgs84.c_str());
  to.importFromWkt(source.crsWkt.c_str());
  from.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  to.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<OGRCoordinateTransformation, void (*)(OGRCoordinateTransformation*)> transform(
      OGRCreateCoordinateTransformation(&from, &to), OGRCoordinateTransformation::DestroyCT);
  if (!transform)
    throw invalidOption("-t_srs: cannot transform from WGS 84 to " + io::crsShortName(source.crsWkt));

  City& city = source.input.city;
  Builder b{osm, city, transform.get(), {}, -1};
  for (const io::OsmWay& way : osm.ways) {
    if (way.highway.empty()) continue;
    city.streets.push_back({way.id, b.wayNodes(way), way.highway, way.name});
  }
  if (city.streets.empty())
    throw invalidInput("OSM file '" + osmPath +
                       "' has no street: no way with a highway tag (city shrinking "
                       "works on the street network)");
  std::vector<std::string> examples;
  if (io::looksLikeOsmi(importancePath)) {
    readOsmi(b, importancePath, source.input.places, source.missingIds, examples);
  } else {
    std::error_code ec;
    if (!std::filesystem::exists(importancePath, ec))
      throw invalidInput("importance file '" + importancePath + "' does not exist");
    readImportanceLayers(b, importancePath, options, source.crsWkt, source.input.places);
  }
  if (source.missingIds > 0 && warn) {
    std::string list;
    for (const std::string& e : examples) list += (list.empty() ? "" : ", ") + e;
    warn(std::to_string(source.missingIds) + " member id" + (source.missingIds == 1 ? " of '" : "s of '") +
         importancePath + "' " + (source.missingIds == 1 ? "is" : "are") + " not in '" + osmPath + "' (" +
         list + (source.missingIds > static_cast<int>(examples.size()) ? ", ..." : "") +
         "); going on without " + (source.missingIds == 1 ? "it" : "them"));
  }
  return source;
}

}  // namespace urbanvec::app
