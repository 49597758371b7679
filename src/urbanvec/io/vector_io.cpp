#include "urbanvec/io/vector_io.hpp"

#include <cpl_string.h>
#include <gdal_priv.h>
#include <ogr_geometry.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <memory>
#include <tuple>

#include "urbanvec/core/error.hpp"
#include "urbanvec/io/gdal_init.hpp"
#include "urbanvec/io/layer_styles.hpp"

namespace urbanvec::io {

namespace {

struct DatasetCloser {
  void operator()(GDALDataset* ds) const { GDALClose(ds); }
};
using DatasetPtr = std::unique_ptr<GDALDataset, DatasetCloser>;

OGRwkbGeometryType ogrType(GeometryType t) {
  switch (t) {
    case GeometryType::None:
      return wkbNone;
    case GeometryType::Point:
      return wkbPoint;
    case GeometryType::LineString:
      return wkbLineString;
    case GeometryType::Polygon:
      return wkbPolygon;
    case GeometryType::MultiPolygon:
      return wkbMultiPolygon;
    case GeometryType::MultiLineString:
      return wkbMultiLineString;
  }
  return wkbUnknown;
}

void fillLine(OGRSimpleCurve& curve, const LineString& points) {
  curve.setNumPoints(static_cast<int>(points.size()), FALSE);
  for (size_t i = 0; i < points.size(); ++i) curve.setPoint(static_cast<int>(i), points[i].x, points[i].y);
}

std::unique_ptr<OGRPolygon> toOgrPolygon(const Polygon& polygon) {
  auto out = std::make_unique<OGRPolygon>();
  auto addRing = [&](const Ring& r) {
    auto ring = std::make_unique<OGRLinearRing>();
    fillLine(*ring, r);
    ring->closeRings();
    out->addRingDirectly(ring.release());
  };
  addRing(polygon.outer);
  for (const Ring& hole : polygon.holes) addRing(hole);
  return out;
}

std::unique_ptr<OGRGeometry> toOgr(const Geometry& geometry) {
  struct Visitor {
    std::unique_ptr<OGRGeometry> operator()(std::monostate) const { return nullptr; }
    std::unique_ptr<OGRGeometry> operator()(const Vec2& p) const {
      return std::make_unique<OGRPoint>(p.x, p.y);
    }
    std::unique_ptr<OGRGeometry> operator()(const LineString& l) const {
      auto line = std::make_unique<OGRLineString>();
      fillLine(*line, l);
      return line;
    }
    std::unique_ptr<OGRGeometry> operator()(const Polygon& p) const { return toOgrPolygon(p); }
    std::unique_ptr<OGRGeometry> operator()(const MultiPolygon& mp) const {
      auto out = std::make_unique<OGRMultiPolygon>();
      for (const Polygon& p : mp) out->addGeometryDirectly(toOgrPolygon(p).release());
      return out;
    }
    std::unique_ptr<OGRGeometry> operator()(const MultiLineString& ml) const {
      auto out = std::make_unique<OGRMultiLineString>();
      for (const LineString& l : ml) {
        auto line = std::make_unique<OGRLineString>();
        fillLine(*line, l);
        out->addGeometryDirectly(line.release());
      }
      return out;
    }
  };
  return std::visit(Visitor{}, geometry);
}

LineString fromCurve(const OGRSimpleCurve& curve) {
  LineString out(static_cast<size_t>(curve.getNumPoints()));
  for (int i = 0; i < curve.getNumPoints(); ++i) out[static_cast<size_t>(i)] = {curve.getX(i), curve.getY(i)};
  return out;
}

Polygon fromOgrPolygon(const OGRPolygon& polygon) {
  Polygon out;
  if (const OGRLinearRing* exterior = polygon.getExteriorRing()) out.outer = fromCurve(*exterior);
  for (int i = 0; i < polygon.getNumInteriorRings(); ++i)
    out.holes.push_back(fromCurve(*polygon.getInteriorRing(i)));
  return out;
}

Geometry fromOgr(const OGRGeometry* geometry) {
  if (!geometry || geometry->IsEmpty()) return std::monostate{};
  std::unique_ptr<OGRGeometry> linear;
  if (geometry->hasCurveGeometry()) {
    linear.reset(geometry->getLinearGeometry());
    geometry = linear.get();
  }
  switch (wkbFlatten(geometry->getGeometryType())) {
    case wkbPoint: {
      const auto* p = geometry->toPoint();
      return Vec2{p->getX(), p->getY()};
    }
    case wkbLineString:
      return fromCurve(*geometry->toLineString());
    case wkbPolygon:
      return fromOgrPolygon(*geometry->toPolygon());
    case wkbMultiPolygon: {
      MultiPolygon out;
      for (const OGRPolygon* p : *geometry->toMultiPolygon()) out.push_back(fromOgrPolygon(*p));
      return out;
    }
    case wkbMultiLineString: {
      MultiLineString out;
      for (const OGRLineString* l : *geometry->toMultiLineString()) out.push_back(fromCurve(*l));
      return out;
    }
    case wkbMultiPoint: {
      const auto* mp = geometry->toMultiPoint();
      if (mp->getNumGeometries() > 0) {
        const auto* p = static_cast<const OGRPoint*>(mp->getGeometryRef(0));
        return Vec2{p->getX(), p->getY()};
      }
      return std::monostate{};
    }
    case wkbGeometryCollection: {
      // Keep the polygonal or linear parts, whichever the collection holds first.
      MultiPolygon polygons;
      MultiLineString lines;
      for (const OGRGeometry* part : *geometry->toGeometryCollection()) {
        Geometry g = fromOgr(part);
        if (auto* p = std::get_if<Polygon>(&g)) polygons.push_back(*p);
        if (auto* mp = std::get_if<MultiPolygon>(&g)) polygons.insert(polygons.end(), mp->begin(), mp->end());
        if (auto* l = std::get_if<LineString>(&g)) lines.push_back(*l);
        if (auto* ml = std::get_if<MultiLineString>(&g)) lines.insert(lines.end(), ml->begin(), ml->end());
      }
      if (!polygons.empty()) return polygons;
      if (!lines.empty()) return lines;
      return std::monostate{};
    }
    default:
      return std::monostate{};
  }
}

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

DatasetPtr openVector(const std::string& path, const std::string& role) {
  ensureGdal();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec) && path.rfind("/vsi", 0) != 0)
    throw invalidInput(role + " '" + path + "' does not exist");
  CPLErrorReset();
  DatasetPtr ds(static_cast<GDALDataset*>(
      GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
  if (!ds) {
    std::string why = lastGdalMessage();
    throw invalidInput(role + " '" + path + "' is not a vector dataset GDAL can read" +
                       (why.empty() ? "" : " (" + why + ")"));
  }
  return ds;
}

const char* kStyleTable = "layer_styles";

void writeLayerStyles(GDALDataset& ds, const std::map<std::string, std::string>& styles) {
  if (styles.empty()) return;
  OGRLayer* table = ds.CreateLayer(kStyleTable, nullptr, wkbNone, nullptr);
  if (!table) throw ioError("cannot create the layer_styles table (" + std::string(lastGdalMessage()) + ")");
  const char* names[] = {"f_table_catalog", "f_table_schema",
                         "f_table_name",    "f_geometry_column",
                         "styleName",       "styleQML",
                         "styleSLD",        "description",
                         "owner",           "ui"};
  for (const char* n : names) {
    OGRFieldDefn f(n, OFTString);
    table->CreateField(&f);
  }
  OGRFieldDefn useAsDefault("useAsDefault", OFTInteger);
  useAsDefault.SetSubType(OFSTBoolean);
  table->CreateField(&useAsDefault);
  OGRFieldDefn updated("update_time", OFTDateTime);
  table->CreateField(&updated);
  std::vector<std::tuple<std::string, std::string, std::string, bool>> rows;  // layer, style, QML, default
  for (const auto& [layerName, qml] : styles) {
    rows.emplace_back(layerName, layerName, qml, true);
    for (const auto& [styleName, alternative] : alternativeStylesFor(layerName))
      rows.emplace_back(layerName, styleName, alternative, false);
  }
  for (const auto& [layerName, styleName, qml, isDefault] : rows) {
    OGRFeature feature(table->GetLayerDefn());
    feature.SetField("f_table_catalog", "");
    feature.SetField("f_table_schema", "");
    feature.SetField("f_table_name", layerName.c_str());
    feature.SetField("f_geometry_column", "geom");
    feature.SetField("styleName", styleName.c_str());
    feature.SetField("styleQML", qml.c_str());
    feature.SetField("styleSLD", "");
    feature.SetField("useAsDefault", isDefault ? 1 : 0);
    feature.SetField("description", isDefault ? "urbanvec default style" : "urbanvec style");
    feature.SetField("owner", "");
    feature.SetField("ui", "");
    feature.SetField("update_time", 2026, 1, 1, 0, 0, 0, 0);
    if (table->CreateFeature(&feature) != OGRERR_NONE)
      throw ioError("cannot write the style of layer '" + layerName + "'");
  }
}

}  // namespace

std::string vectorFormatFor(const std::string& path, const std::string& requestedFormat) {
  if (!requestedFormat.empty()) return requestedFormat;
  const std::string ext = lowerExtension(path);
  if (ext == ".shp") return "ESRI Shapefile";
  if (ext == ".geojson" || ext == ".json") return "GeoJSON";
  if (ext == ".fgb") return "FlatGeobuf";
  if (ext == ".sqlite") return "SQLite";
  if (ext == ".gml") return "GML";
  if (ext == ".kml") return "KML";
  if (ext == ".csv") return "CSV";
  return "GPKG";
}

void writeVectorDataset(const std::string& path, const std::vector<Layer>& layers,
                        const VectorWriteOptions& options) {
  ensureGdal();
  const std::string format = vectorFormatFor(path, options.format);
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(format.c_str());
  if (!driver || !driver->GetMetadataItem(GDAL_DCAP_VECTOR) || !driver->GetMetadataItem(GDAL_DCAP_CREATE))
    throw invalidOption("-of: '" + format + "' is not a vector format GDAL can write");
  CPLStringList dsco;
  for (const std::string& kv : options.datasetCreationOptions) dsco.AddString(kv.c_str());
  CPLErrorReset();
  DatasetPtr ds(driver->Create(path.c_str(), 0, 0, 0, GDT_Unknown, dsco.List()));
  if (!ds) throw ioError("cannot create '" + path + "' (" + std::string(lastGdalMessage()) + ")");
  OGRSpatialReference srs;
  const bool hasSrs = !options.crsWkt.empty() && srs.importFromWkt(options.crsWkt.c_str()) == OGRERR_NONE;
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  const bool transactions = ds->TestCapability(ODsCTransactions);
  if (transactions) ds->StartTransaction();
  for (const Layer& layer : layers) {
    CPLStringList lco;
    for (const std::string& kv : options.layerCreationOptions) lco.AddString(kv.c_str());
    OGRLayer* out = ds->CreateLayer(layer.name.c_str(),
                                    hasSrs && layer.geometryType != GeometryType::None ? &srs : nullptr,
                                    ogrType(layer.geometryType), lco.List());
    if (!out)
      throw ioError("cannot create layer '" + layer.name + "' in '" + path + "' (" + lastGdalMessage() + ")");
    for (const FieldDef& f : layer.fields) {
      OGRFieldDefn defn(f.name.c_str(), f.type == FieldType::Integer ? OFTInteger64
                                        : f.type == FieldType::Real  ? OFTReal
                                                                     : OFTString);
      if (out->CreateField(&defn) != OGRERR_NONE)
        throw ioError("cannot create field '" + f.name + "' of layer '" + layer.name + "'");
    }
    OGRFeatureDefn* defn = out->GetLayerDefn();
    for (const Feature& feature : layer.features) {
      OGRFeature f(defn);
      for (size_t i = 0; i < feature.values.size() && i < layer.fields.size(); ++i) {
        const int idx = static_cast<int>(i);
        std::visit(
            [&](const auto& v) {
              using V = std::decay_t<decltype(v)>;
              if constexpr (std::is_same_v<V, std::monostate>)
                f.SetFieldNull(idx);
              else if constexpr (std::is_same_v<V, std::int64_t>)
                f.SetField(idx, static_cast<GIntBig>(v));
              else if constexpr (std::is_same_v<V, double>)
                f.SetField(idx, v);
              else
                f.SetField(idx, v.c_str());
            },
            feature.values[i]);
      }
      if (auto g = toOgr(feature.geometry)) {
        if (layer.geometryType == GeometryType::MultiPolygon &&
            wkbFlatten(g->getGeometryType()) == wkbPolygon)
          g.reset(OGRGeometryFactory::forceToMultiPolygon(g.release()));
        f.SetGeometryDirectly(g.release());
      }
      if (out->CreateFeature(&f) != OGRERR_NONE)
        throw ioError("cannot write a feature of layer '" + layer.name + "' (" + lastGdalMessage() + ")");
    }
  }
  if (format == "GPKG") {
    std::map<std::string, std::string> styles = options.layerStylesQml;
    if (options.defaultStyles)
      for (const Layer& layer : layers)
        if (!styles.count(layer.name) && !defaultStyleFor(layer.name).empty())
          styles[layer.name] = defaultStyleFor(layer.name);
    writeLayerStyles(*ds, styles);
  }
  if (transactions && ds->CommitTransaction() != OGRERR_NONE)
    throw ioError("cannot write '" + path + "' (" + std::string(lastGdalMessage()) + ")");
  CPLErrorReset();
  GDALClose(ds.release());
  if (CPLGetLastErrorType() >= CE_Failure)
    throw ioError("cannot finish '" + path + "' (" + std::string(lastGdalMessage()) + ")");
}

std::vector<std::string> listVectorLayers(const std::string& path, const std::string& role) {
  DatasetPtr ds = openVector(path, role);
  std::vector<std::string> names;
  for (int i = 0; i < ds->GetLayerCount(); ++i) names.emplace_back(ds->GetLayer(i)->GetName());
  return names;
}

std::optional<LayerRead> readVectorLayer(const std::string& path, const std::string& layerName,
                                         const std::string& role, const VectorReadOptions& options) {
  DatasetPtr ds = openVector(path, role);
  OGRLayer* in = ds->GetLayerByName(layerName.c_str());
  if (!in) return std::nullopt;
  LayerRead result;
  Layer& layer = result.layer;
  layer.name = layerName;
  const OGRwkbGeometryType type = wkbFlatten(in->GetGeomType());
  layer.geometryType = type == wkbNone              ? GeometryType::None
                       : type == wkbPoint           ? GeometryType::Point
                       : type == wkbLineString      ? GeometryType::LineString
                       : type == wkbPolygon         ? GeometryType::Polygon
                       : type == wkbMultiLineString ? GeometryType::MultiLineString
                                                    : GeometryType::MultiPolygon;
  OGRFeatureDefn* defn = in->GetLayerDefn();
  for (int i = 0; i < defn->GetFieldCount(); ++i) {
    const OGRFieldType t = defn->GetFieldDefn(i)->GetType();
    layer.fields.push_back({defn->GetFieldDefn(i)->GetNameRef(), t == OFTInteger || t == OFTInteger64
                                                                     ? FieldType::Integer
                                                                 : t == OFTReal ? FieldType::Real
                                                                                : FieldType::String});
  }
  std::unique_ptr<OGRCoordinateTransformation> transform;
  if (const OGRSpatialReference* srs = in->GetSpatialRef()) {
    char* wkt = nullptr;
    if (srs->exportToWkt(&wkt) == OGRERR_NONE && wkt) result.crsWkt = wkt;
    CPLFree(wkt);
    if (!options.targetCrs.empty()) {
      OGRSpatialReference source(*srs), target;
      if (target.SetFromUserInput(options.targetCrs.c_str()) != OGRERR_NONE)
        throw invalidOption("cannot understand the CRS '" + options.targetCrs + "'");
      source.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
      target.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
      transform.reset(OGRCreateCoordinateTransformation(&source, &target));
      if (!transform)
        throw invalidInput(role + " '" + path + "': cannot transform layer '" + layerName +
                           "' to the output CRS");
    }
  }
  in->ResetReading();
  CPLErrorReset();
  while (OGRFeature* raw = in->GetNextFeature()) {
    std::unique_ptr<OGRFeature> f(raw);
    Feature out;
    for (int i = 0; i < defn->GetFieldCount(); ++i) {
      if (!f->IsFieldSetAndNotNull(i)) {
        out.values.emplace_back(std::monostate{});
        continue;
      }
      switch (layer.fields[static_cast<size_t>(i)].type) {
        case FieldType::Integer:
          out.values.emplace_back(static_cast<std::int64_t>(f->GetFieldAsInteger64(i)));
          break;
        case FieldType::Real:
          out.values.emplace_back(f->GetFieldAsDouble(i));
          break;
        case FieldType::String:
          out.values.emplace_back(std::string(f->GetFieldAsString(i)));
          break;
      }
    }
    if (OGRGeometry* g = f->GetGeometryRef()) {
      if (transform && g->transform(transform.get()) != OGRERR_NONE) continue;
      out.geometry = fromOgr(g);
    }
    layer.features.push_back(std::move(out));
  }
  return result;
}

}  // namespace urbanvec::io
