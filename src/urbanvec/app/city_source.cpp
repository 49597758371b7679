// Reading city vectors with OGR (issue 2 §2 "Input": OSM through GDAL's OSM driver, GeoPackage and
// shapefile layers named by options).
#include "urbanvec/app/city_source.hpp"

#include <gdal_priv.h>
#include <ogr_geometry.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <filesystem>
#include <memory>
#include <optional>

#include "urbanvec/core/error.hpp"
#include "urbanvec/core/utm.hpp"
#include "urbanvec/io/crs.hpp"
#include "urbanvec/io/gdal_init.hpp"
#include "urbanvec/io/gdal_types.hpp"

namespace urbanvec::app {

// The adapters read files through io's readers and helpers.
using namespace urbanvec::io;

namespace {

using gridify::CityData;
using gridify::Tags;

struct TransformDeleter {
  void operator()(OGRCoordinateTransformation* t) const { OGRCoordinateTransformation::DestroyCT(t); }
};

/// Linear parts of a geometry.
void collectLines(const OGRGeometry* g, MultiLineString& out) {
  if (!g || g->IsEmpty()) return;
  switch (wkbFlatten(g->getGeometryType())) {
    case wkbLineString:
      out.push_back(fromOgrCurve(*g->toLineString()));
      break;
    case wkbMultiLineString:
    case wkbGeometryCollection:
    case wkbMultiPolygon:
      for (const OGRGeometry* part : *g->toGeometryCollection()) collectLines(part, out);
      break;
    default:
      break;
  }
}

/// Polygonal parts of a geometry.
void collectPolygons(const OGRGeometry* g, MultiPolygon& out) {
  if (!g || g->IsEmpty()) return;
  switch (wkbFlatten(g->getGeometryType())) {
    case wkbPolygon:
      out.push_back(fromOgrPolygon(*g->toPolygon()));
      break;
    case wkbMultiPolygon:
    case wkbGeometryCollection:
      for (const OGRGeometry* part : *g->toGeometryCollection()) collectPolygons(part, out);
      break;
    default:
      break;
  }
}

enum class Shape { Lines, Polygons };

std::string layerList(GDALDataset& ds) {
  std::string names;
  for (OGRLayer* layer : ds.GetLayers()) names += (names.empty() ? "" : ", ") + std::string(layer->GetName());
  return names.empty() ? "none" : names;
}

/// The layer named by `option`, or the first existing conventional name when the option is empty.
OGRLayer* pickLayer(GDALDataset& ds, const std::string& path, const std::string& option,
                    const std::string& given, const std::vector<std::string>& conventional, Shape shape,
                    bool required) {
  OGRLayer* layer = nullptr;
  if (!given.empty()) {
    layer = ds.GetLayerByName(given.c_str());
    if (!layer)
      throw invalidInput(option + ": input '" + path + "' has no layer '" + given +
                         "' (layers: " + layerList(ds) + ")");
  } else {
    for (const std::string& name : conventional)
      if ((layer = ds.GetLayerByName(name.c_str()))) break;
    if (!layer && required)
      throw invalidInput("input '" + path + "' has no roads layer (looked for " + conventional.front() +
                         ", " + conventional.back() + "; layers: " + layerList(ds) + "); name it with " +
                         option);
    if (!layer) return nullptr;
  }
  const OGRwkbGeometryType type = wkbFlatten(layer->GetGeomType());
  const bool lines = type == wkbLineString || type == wkbMultiLineString;
  const bool polygons = type == wkbPolygon || type == wkbMultiPolygon;
  const bool unknown = type == wkbUnknown || type == wkbGeometryCollection;
  if (!unknown && ((shape == Shape::Lines && !lines) || (shape == Shape::Polygons && !polygons)))
    throw invalidInput(option + ": layer '" + std::string(layer->GetName()) + "' of '" + path + "' holds " +
                       OGRGeometryTypeToName(type) + " geometries, not " +
                       (shape == Shape::Lines ? "lines" : "polygons"));
  return layer;
}

int fieldIndex(OGRLayer* layer, const std::string& name) {
  return name.empty() ? -1 : layer->GetLayerDefn()->GetFieldIndex(name.c_str());
}

std::string fieldText(const OGRFeature& f, int index) {
  if (index < 0 || !f.IsFieldSetAndNotNull(index)) return "";
  return f.GetFieldAsString(index);
}

/// All tags of an OSM feature: its own fields plus the other_tags hstore.
Tags osmTags(const OGRFeature& f) {
  Tags tags;
  const OGRFeatureDefn* defn = f.GetDefnRef();
  for (int i = 0; i < defn->GetFieldCount(); ++i) {
    if (!f.IsFieldSetAndNotNull(i)) continue;
    const std::string name = defn->GetFieldDefn(i)->GetNameRef();
    if (name == "other_tags") {
      for (auto& [k, v] : gridify::parseHstore(f.GetFieldAsString(i))) tags.emplace(k, v);
    } else if (name != "osm_id" && name != "osm_way_id") {
      tags[name] = f.GetFieldAsString(i);
    }
  }
  return tags;
}

/// While it lives, records the failures GDAL reports (its quiet handler would drop them): a driver
/// that meets a broken or truncated file (the OSM driver: "An error occurred during the parsing of
/// data around byte N") reports a failure and then ends the layer early, as if it had no more features.
class ReadFailures {
 public:
  ReadFailures() { CPLPushErrorHandlerEx(handler, this); }
  ~ReadFailures() { CPLPopErrorHandler(); }
  ReadFailures(const ReadFailures&) = delete;
  ReadFailures& operator=(const ReadFailures&) = delete;
  bool any() const { return count_ > 0; }
  const std::string& first() const { return first_; }

 private:
  static void CPL_STDCALL handler(CPLErr kind, CPLErrorNum, const char* message) {
    auto* self = static_cast<ReadFailures*>(CPLGetErrorHandlerUserData());
    if (!self || kind < CE_Failure) return;
    if (self->count_++ == 0) self->first_ = message ? message : "";
  }
  int count_ = 0;
  std::string first_;
};

struct Reader {
  const std::string& path;
  OGRCoordinateTransformation* transform;

  /// Calls fn(feature, geometry in the grid CRS) for every feature with a geometry. Throws when GDAL
  /// reported a failure while reading, since the features read are then only part of the layer.
  template <class Fn>
  void each(OGRLayer* layer, Fn fn) {
    std::optional<ReadFailures> failures(std::in_place);
    layer->ResetReading();
    std::unique_ptr<OGRFeature> f;
    while ((f.reset(layer->GetNextFeature()), f)) {
      OGRGeometry* g = f->GetGeometryRef();
      if (!g || g->IsEmpty()) continue;
      if (transform && g->transform(transform) != OGRERR_NONE)
        throw invalidInput("cannot reproject a feature of layer '" + std::string(layer->GetName()) +
                           "' of '" + path + "' (" + lastGdalMessage() + ")");
      fn(*f, g);
    }
    if (failures->any()) {
      const std::string why = failures->first();
      failures.reset();
      throw invalidInput("input '" + path +
                         "' could not be read completely: GDAL failed while reading layer '" +
                         layer->GetName() + "'" + (why.empty() ? "" : " (" + why + ")") +
                         "; the file may be truncated or damaged, so download or export it again");
    }
  }
};

OGRSpatialReference srsFromWkt(const std::string& wkt) {
  OGRSpatialReference srs;
  srs.importFromWkt(wkt.c_str());
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  return srs;
}

}  // namespace

std::string chooseGridCrs(const std::string& sourceWkt, double centreX, double centreY,
                          const std::string& userTarget) {
  if (!userTarget.empty()) {
    const std::string wkt = crsToWkt(userTarget, "-t_srs");
    if (!isProjectedInMetres(wkt))
      throw invalidOption("-t_srs: the grid needs a projected CRS in metres; '" + userTarget +
                          "' is not one");
    return wkt;
  }
  if (isGeographic(sourceWkt))
    return crsToWkt("EPSG:" + std::to_string(utmEpsgFor(centreX, centreY)), "-t_srs");
  if (!isProjectedInMetres(sourceWkt))
    throw invalidOption("-t_srs: the input CRS " + crsShortName(sourceWkt) +
                        " is not projected in metres; give a grid CRS with -t_srs");
  return sourceWkt;
}

CityData readCitySource(const std::string& path, const CitySourceOptions& options,
                        const std::function<void(const std::string&)>& warn) {
  ensureGdal();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw invalidInput("input '" + path + "' does not exist");
  CPLErrorReset();
  DatasetPtr ds(static_cast<GDALDataset*>(
      GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
  if (!ds) {
    const std::string why = lastGdalMessage();
    DatasetPtr raster(static_cast<GDALDataset*>(
        GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
    if (raster)
      throw invalidInput("input '" + path +
                         "' is a raster; gridify needs city vectors (OSM, GeoPackage, shapefile)");
    throw invalidInput("input '" + path + "' is not a vector dataset GDAL can read" +
                       (why.empty() ? "" : " (" + why + ")"));
  }
  const bool osm = std::string(ds->GetDriver()->GetDescription()) == "OSM";

  OGRLayer* roadsLayer = nullptr;
  OGRLayer* buildingsLayer = nullptr;
  OGRLayer* parcelsLayer = nullptr;
  OGRLayer* landuseLayer = nullptr;
  OGRLayer* waterLayer = nullptr;
  if (osm) {
    roadsLayer = ds->GetLayerByName("lines");
    landuseLayer = ds->GetLayerByName("multipolygons");
    if (!roadsLayer || !landuseLayer)
      throw invalidInput("input '" + path + "' lacks the OSM lines/multipolygons layers");
  } else {
    roadsLayer =
        pickLayer(*ds, path, "-roads-layer", options.roadsLayer, {"roads", "streets"}, Shape::Lines, true);
    buildingsLayer = pickLayer(*ds, path, "-buildings-layer", options.buildingsLayer, {"buildings"},
                               Shape::Polygons, false);
    landuseLayer =
        pickLayer(*ds, path, "-landuse-layer", options.landuseLayer, {"landuse"}, Shape::Polygons, false);
    waterLayer = pickLayer(*ds, path, "-water-layer", options.waterLayer, {"water"}, Shape::Polygons, false);
  }
  if (!options.parcelsLayer.empty())
    parcelsLayer = pickLayer(*ds, path, "-parcels-layer", options.parcelsLayer, {}, Shape::Polygons, true);

  // Source CRS and grid CRS.
  std::string sourceWkt;
  if (!options.assignedCrs.empty()) {
    sourceWkt = crsToWkt(options.assignedCrs, "-a_srs");
  } else if (const OGRSpatialReference* srs = roadsLayer->GetSpatialRef()) {
    sourceWkt = wktOf(*srs);
  }
  if (sourceWkt.empty()) throw invalidInput("input '" + path + "' has no CRS; give it with -a_srs");
  OGREnvelope env;
  if (roadsLayer->GetExtent(&env, TRUE) != OGRERR_NONE)
    throw invalidInput("input '" + path + "': the roads layer '" + std::string(roadsLayer->GetName()) +
                       "' has no feature");
  OGRSpatialReference source = srsFromWkt(sourceWkt);
  double cx = (env.MinX + env.MaxX) / 2.0, cy = (env.MinY + env.MaxY) / 2.0;
  // GetExtent reports in the layer's data axis order; with a traditional-order layer x is east.
  CityData city;
  city.crsWkt = chooseGridCrs(sourceWkt, cx, cy, options.targetCrs);
  OGRSpatialReference target = srsFromWkt(city.crsWkt);
  std::unique_ptr<OGRCoordinateTransformation, TransformDeleter> transform;
  if (!source.IsSame(&target)) {
    transform.reset(OGRCreateCoordinateTransformation(&source, &target));
    if (!transform)
      throw invalidOption("-t_srs: cannot transform from " + crsShortName(sourceWkt) + " to " +
                          crsShortName(city.crsWkt));
  }
  Reader reader{path, transform.get()};

  // Roads (and, in OSM, coastlines).
  const int classIndex = fieldIndex(roadsLayer, options.roadClassField);
  const int nameIndex = fieldIndex(roadsLayer, "name");
  std::size_t unclassified = 0;
  reader.each(roadsLayer, [&](const OGRFeature& f, const OGRGeometry* g) {
    MultiLineString lines;
    collectLines(g, lines);
    if (osm) {
      const Tags tags = osmTags(f);
      auto natural = tags.find("natural");
      if (natural != tags.end() && natural->second == "coastline") {
        for (LineString& l : lines) city.coastlines.push_back(std::move(l));
        return;
      }
      auto area = tags.find("area");
      if (area != tags.end() && area->second == "yes") return;
    }
    LandUse cls = options.defaultRoadClass;
    std::string source;
    if (classIndex >= 0) {
      source = fieldText(f, classIndex);
      auto mapped = gridify::roadClassFor(source, options.roadClasses);
      if (!mapped) {
        if (!source.empty() && !osm) ++unclassified;
        return;
      }
      cls = *mapped;
    }
    for (LineString& l : lines)
      if (l.size() >= 2) city.roads.push_back({std::move(l), cls, source, fieldText(f, nameIndex)});
  });
  if (unclassified && warn)
    warn(std::to_string(unclassified) + " features of layer '" + roadsLayer->GetName() + "' of '" + path +
         "' have a road class that is neither primary nor secondary and are not roads");

  if (osm) {
    reader.each(landuseLayer, [&](const OGRFeature& f, const OGRGeometry* g) {
      const Tags tags = osmTags(f);
      MultiPolygon shape;
      collectPolygons(g, shape);
      if (shape.empty()) return;
      auto building = tags.find("building");
      if (building != tags.end() && building->second != "no") {
        gridify::CityBuilding b;
        b.footprint = std::move(shape);
        b.use = gridify::buildingUseForTags(tags);
        auto levels = tags.find("building:levels");
        if (levels != tags.end()) b.levels = gridify::parseLevels(levels->second);
        city.buildings.push_back(std::move(b));
        return;
      }
      auto use = gridify::areaUseForTags(tags);
      if (!use) return;
      if (*use == LandUse::Water)
        city.water.push_back(std::move(shape));
      else
        city.areas.push_back({std::move(shape), *use});
    });
  } else {
    if (buildingsLayer) {
      const int useIndex =
          fieldIndex(buildingsLayer, options.landuseField.empty() ? "building" : options.landuseField);
      const int levelsIndex = fieldIndex(buildingsLayer, options.levelsField);
      reader.each(buildingsLayer, [&](const OGRFeature& f, const OGRGeometry* g) {
        gridify::CityBuilding b;
        collectPolygons(g, b.footprint);
        if (b.footprint.empty()) return;
        b.use = gridify::useFromValue(fieldText(f, useIndex));
        b.levels = gridify::parseLevels(fieldText(f, levelsIndex));
        city.buildings.push_back(std::move(b));
      });
    }
    if (landuseLayer) {
      const std::string field = options.landuseField.empty() ? "landuse" : options.landuseField;
      const int useIndex = fieldIndex(landuseLayer, field);
      if (useIndex < 0)
        throw invalidOption("-landuse-field: layer '" + std::string(landuseLayer->GetName()) + "' of '" +
                            path + "' has no field '" + field + "'");
      reader.each(landuseLayer, [&](const OGRFeature& f, const OGRGeometry* g) {
        MultiPolygon shape;
        collectPolygons(g, shape);
        auto use = gridify::useFromValue(fieldText(f, useIndex));
        if (shape.empty() || !use) return;
        if (*use == LandUse::Water)
          city.water.push_back(std::move(shape));
        else
          city.areas.push_back({std::move(shape), *use});
      });
    }
    if (waterLayer) {
      reader.each(waterLayer, [&](const OGRFeature&, const OGRGeometry* g) {
        MultiPolygon shape;
        collectPolygons(g, shape);
        if (!shape.empty()) city.water.push_back(std::move(shape));
      });
    }
  }

  if (parcelsLayer) {
    const int useIndex = fieldIndex(parcelsLayer, options.landuseField);
    const int popIndex = fieldIndex(parcelsLayer, options.populationField);
    if (!options.populationField.empty() && popIndex < 0)
      throw invalidOption("-population-field: layer '" + std::string(parcelsLayer->GetName()) + "' of '" +
                          path + "' has no field '" + options.populationField + "'");
    reader.each(parcelsLayer, [&](const OGRFeature& f, const OGRGeometry* g) {
      gridify::CityParcel p;
      collectPolygons(g, p.shape);
      if (p.shape.empty()) return;
      p.use = gridify::useFromValue(fieldText(f, useIndex));
      if (popIndex >= 0 && f.IsFieldSetAndNotNull(popIndex)) p.population = f.GetFieldAsDouble(popIndex);
      p.sourceId = std::to_string(f.GetFID());
      city.parcels.push_back(std::move(p));
    });
    if (city.parcels.empty())
      throw invalidInput("-parcels-layer: layer '" + options.parcelsLayer + "' of '" + path +
                         "' has no polygon");
  }
  if (city.roads.empty())
    throw invalidInput("input '" + path + "' holds no road (layer '" + roadsLayer->GetName() +
                       "'); check -roads-layer and -road-class-field");
  return city;
}

}  // namespace urbanvec::app
