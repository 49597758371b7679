#include "urbanvec/io/vector_io.hpp"

#include <cpl_string.h>
#include <gdal_priv.h>
#include <ogr_geometry.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <thread>
#include <tuple>

#include "urbanvec/core/error.hpp"
#include "urbanvec/io/atomic_output.hpp"
#include "urbanvec/io/creation_options.hpp"
#include "urbanvec/io/gdal_init.hpp"
#include "urbanvec/io/gdal_types.hpp"
#include "urbanvec/io/layer_styles.hpp"

namespace urbanvec::io {

namespace {

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
      return fromOgrCurve(*geometry->toLineString());
    case wkbPolygon:
      return fromOgrPolygon(*geometry->toPolygon());
    case wkbMultiPolygon: {
      MultiPolygon out;
      for (const OGRPolygon* p : *geometry->toMultiPolygon()) out.push_back(fromOgrPolygon(*p));
      return out;
    }
    case wkbMultiLineString: {
      MultiLineString out;
      for (const OGRLineString* l : *geometry->toMultiLineString()) out.push_back(fromOgrCurve(*l));
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

GDALDriver* vectorDriver(const std::string& format) {
  ensureGdal();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(format.c_str());
  if (!driver || !driver->GetMetadataItem(GDAL_DCAP_VECTOR) || !driver->GetMetadataItem(GDAL_DCAP_CREATE))
    throw invalidOption("-of: '" + format + "' is not a vector format GDAL can write");
  return driver;
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

/// One dataset being written: created (inside one transaction where the driver has them) by the
/// constructor, then one layer at a time, then finish(). Destroyed unfinished, it closes what it
/// wrote (the caller's staging is removed).
class DatasetWriter {
 public:
  DatasetWriter(std::string path, const VectorWriteOptions& options)
      : path_(std::move(path)), options_(options), format_(vectorFormatFor(path_, options.format)) {
    GDALDriver* driver = vectorDriver(format_);
    // GeoPackage stamps each table with the time of writing; a fixed stamp keeps the same input and
    // seed giving byte-identical files (a user's own OGR_CURRENT_DATE wins).
    if (!CPLGetConfigOption("OGR_CURRENT_DATE", nullptr))
      CPLSetConfigOption("OGR_CURRENT_DATE", "2026-01-01T00:00:00.000Z");
    CPLStringList dsco;
    for (const std::string& kv : options.datasetCreationOptions) dsco.AddString(kv.c_str());
    CPLErrorReset();
    ds_.reset(driver->Create(path_.c_str(), 0, 0, 0, GDT_Unknown, dsco.List()));
    if (!ds_) throw ioError("cannot create '" + path_ + "' (" + std::string(lastGdalMessage()) + ")");
    hasSrs_ = !options.crsWkt.empty() && srs_.importFromWkt(options.crsWkt.c_str()) == OGRERR_NONE;
    srs_.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    transactions_ = ds_->TestCapability(ODsCTransactions);
    if (transactions_) ds_->StartTransaction();
  }

  /// Writes one layer. `stop`, when set, abandons the writing between features (returns false).
  bool writeLayer(const Layer& layer, const std::atomic<bool>* stop = nullptr) {
    static std::atomic<long> featuresWritten{0};
    const long failAfter = faultSetting("write-fail-after");
    if (const long delay = faultSetting("write-delay-ms"))
      for (long slept = 0; slept < delay && !(stop && *stop); slept += 10)
        std::this_thread::sleep_for(std::chrono::milliseconds(std::min(10L, delay - slept)));
    CPLStringList lco;
    for (const std::string& kv : options_.layerCreationOptions) lco.AddString(kv.c_str());
    OGRLayer* out = ds_->CreateLayer(layer.name.c_str(),
                                     hasSrs_ && layer.geometryType != GeometryType::None ? &srs_ : nullptr,
                                     ogrType(layer.geometryType), lco.List());
    if (!out)
      throw ioError("cannot create layer '" + layer.name + "' in '" + path_ + "' (" + lastGdalMessage() +
                    ")");
    names_.push_back(layer.name);
    for (const FieldDef& f : layer.fields) {
      OGRFieldDefn defn(f.name.c_str(), f.type == FieldType::Integer ? OFTInteger64
                                        : f.type == FieldType::Real  ? OFTReal
                                                                     : OFTString);
      if (out->CreateField(&defn) != OGRERR_NONE)
        throw ioError("cannot create field '" + f.name + "' of layer '" + layer.name + "'");
    }
    OGRFeatureDefn* defn = out->GetLayerDefn();
    for (const Feature& feature : layer.features) {
      if (stop && *stop) return false;
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
      if (failAfter > 0 && ++featuresWritten >= failAfter)
        throw ioError("cannot write a feature of layer '" + layer.name +
                      "' (fault injected by URBANVEC_FAULT)");
    }
    // The layer is complete: GeoPackage builds its spatial index now (it defers the index until the
    // layer is synced or the dataset closed), so a writer running beside the computation does that
    // work there too, not all at the end.
    if (out->SyncToDisk() != OGRERR_NONE)
      throw ioError("cannot write layer '" + layer.name + "' (" + std::string(lastGdalMessage()) + ")");
    return true;
  }

  /// The layer styles (GeoPackage), the commit, the close.
  void finish() {
    if (format_ == "GPKG") {
      std::map<std::string, std::string> styles = options_.layerStylesQml;
      if (options_.defaultStyles)
        for (const std::string& name : names_)
          if (!styles.count(name) && !defaultStyleFor(name).empty()) styles[name] = defaultStyleFor(name);
      writeLayerStyles(*ds_, styles);
    }
    if (transactions_ && ds_->CommitTransaction() != OGRERR_NONE)
      throw ioError("cannot write '" + path_ + "' (" + std::string(lastGdalMessage()) + ")");
    CPLErrorReset();
    GDALClose(ds_.release());
    if (CPLGetLastErrorType() >= CE_Failure)
      throw ioError("cannot finish '" + path_ + "' (" + std::string(lastGdalMessage()) + ")");
  }

 private:
  std::string path_;
  const VectorWriteOptions& options_;
  std::string format_;
  DatasetPtr ds_;
  OGRSpatialReference srs_;
  bool hasSrs_ = false;
  bool transactions_ = false;
  std::vector<std::string> names_;  ///< the layers written, in order
};

void writeVectorDataset(const std::string& path, const std::vector<Layer>& layers,
                        const VectorWriteOptions& options) {
  DatasetWriter writer(path, options);
  for (const Layer& layer : layers) writer.writeLayer(layer);
  writer.finish();
}

namespace {

/// Files a driver writes beside the named one (checked before the work, moved with it).
std::vector<std::string> sideFiles(const std::string& format, const std::string& fileName) {
  const std::string stem = std::filesystem::path(fileName).stem().string();
  std::vector<std::string> out;
  if (format == "ESRI Shapefile")
    for (const char* ext : {".shp", ".shx", ".dbf", ".prj", ".cpg"}) out.push_back(stem + ext);
  else if (format == "GML")
    out.push_back(stem + ".xsd");
  else if (format == "MapInfo File" && lowerExtension(fileName) == ".mif")
    for (const char* ext : {".mif", ".mid"}) out.push_back(stem + ext);
  else if (format == "MapInfo File")  // the TAB flavour; a .mif/.mid pair of that name is another file
    for (const char* ext : {".tab", ".dat", ".map", ".id"}) out.push_back(stem + ext);
  out.erase(std::remove(out.begin(), out.end(), fileName), out.end());
  return out;
}

}  // namespace

VectorOutput::VectorOutput(std::string path, VectorWriteOptions options, std::vector<std::string> layerNames,
                           OutputRules rules)
    : path_(std::move(path)), options_(std::move(options)) {
  options_.format = vectorFormatFor(path_, options_.format);
  GDALDriver* driver = vectorDriver(options_.format);
  checkCreationOptions(driver->GetMetadataItem(GDAL_DMD_CREATIONOPTIONLIST), options_.datasetCreationOptions,
                       "-dsco", "dataset", options_.format);
  checkCreationOptions(driver->GetMetadataItem(GDAL_DS_LAYER_CREATIONOPTIONLIST),
                       options_.layerCreationOptions, "-lco", "layer", options_.format);
  const char* extensions = driver->GetMetadataItem(GDAL_DMD_EXTENSIONS);
  if (!extensions) extensions = driver->GetMetadataItem(GDAL_DMD_EXTENSION);
  const CPLStringList formatExtensions(CSLTokenizeString(extensions ? extensions : ""));
  layerPerFile_ = layerNames.size() > 1 && !driver->GetMetadataItem(GDAL_DCAP_MULTIPLE_VECTOR_LAYERS);
  if (layerPerFile_) {
    // The extension named like the format where there is one (GeoJSON: .geojson rather than .json).
    std::string chosen = formatExtensions.size() > 0 ? formatExtensions[0] : "";
    for (int i = 0; i < formatExtensions.size(); ++i)
      if (equalsIgnoringCase(formatExtensions[i], options_.format)) chosen = formatExtensions[i];
    extension_ = chosen.empty() ? std::string() : "." + chosen;
    const std::string ext = lowerExtension(path_);
    for (int i = 0; i < formatExtensions.size(); ++i)
      if (!ext.empty() && equalsIgnoringCase(ext.substr(1), formatExtensions[i]))
        throw invalidOption("-of " + options_.format + " holds one layer per file and " +
                            std::to_string(layerNames.size()) + " layers are written: give a folder name " +
                            "instead of '" + path_ + "' (each layer becomes <folder>/<layer>" + extension_ +
                            ")");
    rules.isFolder = true;
    for (const std::string& layer : layerNames) {
      rules.entries.push_back(layer + extension_);
      for (const std::string& side : sideFiles(options_.format, layer + extension_))
        rules.entries.push_back(side);
    }
  } else {
    rules.isFolder = false;
    for (const std::string& side :
         sideFiles(options_.format, std::filesystem::path(path_).filename().string()))
      rules.entries.push_back(side);
  }
  output_ = std::make_unique<AtomicOutput>(path_, std::move(rules));
}

void VectorOutput::write(const std::vector<Layer>& layers, const std::string& crsWkt) {
  if (!crsWkt.empty()) options_.crsWkt = crsWkt;
  if (!layerPerFile_) {
    writeVectorDataset(output_->tempPath(), layers, options_);
    return;
  }
  for (const Layer& layer : layers) {
    DatasetWriter one(layerFile(layer.name), options_);
    one.writeLayer(layer);
    one.finish();
  }
}

std::string VectorOutput::layerFile(const std::string& layer) const {
  return (std::filesystem::path(output_->tempPath()) / (layer + extension_)).string();
}

LayerStream::LayerStream(VectorOutput& output, std::string crsWkt, bool background)
    : output_(output), options_(output.options_) {
  if (!crsWkt.empty()) options_.crsWkt = std::move(crsWkt);
  if (background) thread_ = std::thread([this] { loop(); });
}

LayerStream::~LayerStream() {
  if (thread_.joinable()) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    thread_.join();
  }
  dataset_.reset();  // closes an unfinished dataset before the output's staging goes
}

void LayerStream::write(Layer& layer) {
  if (output_.layerPerFile_) {
    DatasetWriter one(output_.layerFile(layer.name), options_);
    if (one.writeLayer(layer, &stop_)) one.finish();
  } else {
    if (!dataset_) dataset_ = std::make_unique<DatasetWriter>(output_.output_->tempPath(), options_);
    dataset_->writeLayer(layer, &stop_);
  }
  std::vector<Feature>().swap(layer.features);
}

void LayerStream::finishDatasets() {
  if (output_.layerPerFile_) return;
  if (!dataset_) dataset_ = std::make_unique<DatasetWriter>(output_.output_->tempPath(), options_);
  dataset_->finish();
  dataset_.reset();
}

void LayerStream::loop() {
  try {
    for (;;) {
      Layer layer;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait(lock, [this] { return stop_ || finishing_ || !queue_.empty(); });
        if (stop_) return;
        if (queue_.empty()) break;  // finishing, and everything is written
        layer = std::move(queue_.front());
        queue_.pop_front();
      }
      write(layer);
    }
    finishDatasets();
  } catch (...) {
    std::lock_guard<std::mutex> lock(mutex_);
    error_ = std::current_exception();
    queue_.clear();
  }
}

void LayerStream::add(Layer&& layer) {
  if (!thread_.joinable()) {
    write(layer);
    return;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (error_) std::rethrow_exception(error_);
    queue_.push_back(std::move(layer));
  }
  wake_.notify_all();
}

void LayerStream::finish() {
  if (!thread_.joinable()) {
    finishDatasets();
    return;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    finishing_ = true;
  }
  wake_.notify_all();
  thread_.join();
  if (error_) std::rethrow_exception(error_);
}

void VectorOutput::commit(const Progress& progress) {
  output_->commit(progress);
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
  if (!options.where.empty()) {
    CPLErrorReset();
    if (in->SetAttributeFilter(options.where.c_str()) != OGRERR_NONE)
      throw invalidOption("-where: layer '" + layerName + "' of " + role + " '" + path +
                          "' does not accept the filter '" + options.where + "' (" + lastGdalMessage() + ")");
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
  // SQL-backed drivers (GeoPackage) accept any filter and fail only while reading.
  if (!options.where.empty() && CPLGetLastErrorType() >= CE_Failure)
    throw invalidOption("-where: layer '" + layerName + "' of " + role + " '" + path +
                        "' does not accept the filter '" + options.where + "' (" + lastGdalMessage() + ")");
  return result;
}

}  // namespace urbanvec::io
