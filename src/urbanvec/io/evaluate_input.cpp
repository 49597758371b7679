#include "urbanvec/io/evaluate_input.hpp"

#include <cpl_string.h>
#include <cpl_vsi.h>
#include <gdal_utils.h>
#include <ogr_api.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <variant>

#include "urbanvec/core/error.hpp"
#include "urbanvec/io/crs.hpp"
#include "urbanvec/io/gdal_init.hpp"

namespace urbanvec::io {

namespace {

std::string oneLine(std::string message) {
  for (char& c : message)
    if (c == '\n' || c == '\r') c = ' ';
  return message;
}

/// Copies the features of one layer that match `where` into an in-memory GeoPackage, so the filtered
/// layer is read by readVectorLayer like any other; the copy is deleted when this goes out of scope.
class FilteredCopy {
 public:
  FilteredCopy(const std::string& path, const std::string& layerName, const std::string& where,
               const std::string& whereOption) {
    static std::atomic<int> counter{0};
    path_ = "/vsimem/urbanvec_evaluate_" + std::to_string(++counter) + ".gpkg";
    ensureGdal();
    CPLErrorReset();
    GDALDatasetH source =
        GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr);
    if (!source) throw invalidInput("'" + path + "' is not a vector dataset GDAL can read");
    // Try the clause on the layer first, reading one feature since some drivers (GeoPackage) only
    // evaluate it then: GDAL's own reason ("no such column: X") beats ogr2ogr's generic failure.
    OGRLayerH layer = GDALDatasetGetLayerByName(source, layerName.c_str());
    CPLErrorReset();
    bool accepted = layer && OGR_L_SetAttributeFilter(layer, where.c_str()) == OGRERR_NONE;
    if (accepted) {
      OGR_L_ResetReading(layer);
      if (OGRFeatureH first = OGR_L_GetNextFeature(layer)) OGR_F_Destroy(first);
      accepted = CPLGetLastErrorType() < CE_Failure;
    }
    if (!accepted) {
      const std::string why = oneLine(lastGdalMessage());
      GDALClose(source);
      throw invalidOption(whereOption + " '" + where + "' cannot select features of layer '" + layerName +
                          "' of '" + path + "'" + (why.empty() ? "" : " (" + why + ")"));
    }
    OGR_L_SetAttributeFilter(layer, nullptr);
    CPLErrorReset();
    CPLStringList args;
    args.AddString("-f");
    args.AddString("GPKG");
    args.AddString("-where");
    args.AddString(where.c_str());
    args.AddString(layerName.c_str());
    GDALVectorTranslateOptions* options = GDALVectorTranslateOptionsNew(args.List(), nullptr);
    int usageError = 0;
    GDALDatasetH copy =
        options ? GDALVectorTranslate(path_.c_str(), nullptr, 1, &source, options, &usageError) : nullptr;
    const std::string why = oneLine(lastGdalMessage());
    if (options) GDALVectorTranslateOptionsFree(options);
    if (copy) GDALClose(copy);
    GDALClose(source);
    if (!copy || CPLGetLastErrorType() >= CE_Failure) {
      VSIUnlink(path_.c_str());
      throw invalidOption(whereOption + " '" + where + "' cannot select features of layer '" + layerName +
                          "' of '" + path + "'" + (why.empty() ? "" : " (" + why + ")"));
    }
  }
  ~FilteredCopy() { VSIUnlink(path_.c_str()); }
  FilteredCopy(const FilteredCopy&) = delete;
  FilteredCopy& operator=(const FilteredCopy&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

const char* kindName(const Geometry& g) {
  if (std::holds_alternative<Vec2>(g)) return "points";
  if (std::holds_alternative<LineString>(g) || std::holds_alternative<MultiLineString>(g)) return "lines";
  if (std::holds_alternative<Polygon>(g) || std::holds_alternative<MultiPolygon>(g)) return "polygons";
  return nullptr;
}

}  // namespace

std::vector<std::string> listEvaluationLayers(const std::string& path, const std::string& role) {
  try {
    return listVectorLayers(path, role);
  } catch (const Error&) {
    CPLPushErrorHandler(CPLQuietErrorHandler);
    GDALDatasetH raster =
        GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr);
    CPLPopErrorHandler();
    if (raster) {
      GDALClose(raster);
      throw invalidInput(role + " '" + path + "' is a raster, not a vector dataset");
    }
    throw;
  }
}

std::optional<LayerRead> readEvaluationLayer(const std::string& path, const std::string& layerName,
                                             const std::string& where, const std::string& whereOption,
                                             GeometryKind kind, const std::string& role,
                                             const VectorReadOptions& options) {
  const std::vector<std::string> names = listVectorLayers(path, role);
  if (std::find(names.begin(), names.end(), layerName) == names.end()) return std::nullopt;
  std::optional<FilteredCopy> copy;
  if (!where.empty()) copy.emplace(path, layerName, where, whereOption);
  const std::string source = copy ? copy->path() : path;
  std::optional<LayerRead> read = readVectorLayer(source, layerName, role, {});
  if (!read) throw internalError("layer '" + layerName + "' of '" + path + "' vanished while reading it");
  const std::string where_ = "layer '" + layerName + "' of '" + path + "'";
  const char* wanted = kind == GeometryKind::Lines ? "lines" : "polygons";
  if (read->layer.geometryType == GeometryType::None)
    throw invalidInput(role + ": " + where_ + " has no geometry; it must hold " + wanted);
  for (const Feature& f : read->layer.features) {
    const char* found = kindName(f.geometry);
    if (found && std::string(found) != wanted)
      throw invalidInput(role + ": " + where_ + " holds " + found + "; it must hold " + wanted);
  }
  // GeoPackage marks a layer without CRS with an "Undefined geographic SRS" (srs_id 0) or an
  // "Undefined Cartesian SRS" (-1), neither with an authority code: no CRS either.
  OGRSpatialReference crs;
  const bool undefined = read->crsWkt.empty() || crs.importFromWkt(read->crsWkt.c_str()) != OGRERR_NONE ||
                         crs.IsLocal() ||
                         (std::string(crs.GetName() ? crs.GetName() : "").rfind("Undefined ", 0) == 0 &&
                          !crs.GetAuthorityCode(nullptr));
  if (undefined)
    throw invalidInput(role + ": " + where_ + " has no CRS; assign one with ogr2ogr -a_srs" +
                       (options.targetCrs.empty() ? "" : " " + crsShortName(options.targetCrs)));
  if (options.targetCrs.empty()) return read;
  OGRSpatialReference target;
  if (target.SetFromUserInput(options.targetCrs.c_str()) != OGRERR_NONE)
    throw invalidOption("cannot understand the CRS '" + options.targetCrs + "'");
  if (crs.IsSame(&target)) return read;
  std::optional<LayerRead> moved = readVectorLayer(source, layerName, role, options);
  if (!moved || moved->layer.features.size() != read->layer.features.size())
    throw invalidInput(role + ": " + where_ + " cannot be transformed from " + crsShortName(read->crsWkt) +
                       " to " + crsShortName(options.targetCrs));
  return moved;
}

std::optional<double> readGridInfoCellSize(const std::string& truthPath) {
  const std::optional<LayerRead> info = readVectorLayer(truthPath, "grid_info", "truth");
  if (!info) return std::nullopt;
  const Layer& table = info->layer;
  const int field = table.fieldIndex("cell_size");
  std::optional<double> cellSize;
  if (field >= 0 && !table.features.empty()) {
    const FieldValue& v = table.features.front().values[static_cast<size_t>(field)];
    if (const auto* d = std::get_if<double>(&v)) cellSize = *d;
    if (const auto* i = std::get_if<std::int64_t>(&v)) cellSize = static_cast<double>(*i);
    if (const auto* s = std::get_if<std::string>(&v)) {
      char* end = nullptr;
      const double parsed = std::strtod(s->c_str(), &end);
      if (end != s->c_str() && *end == '\0') cellSize = parsed;
    }
  }
  if (!cellSize || !(*cellSize > 0.0) || !std::isfinite(*cellSize))
    throw invalidInput("truth '" + truthPath +
                       "': table grid_info has no positive cell_size; give -cell-size <metres>");
  return cellSize;
}

}  // namespace urbanvec::io
