#include "urbanvec/app/grid_input.hpp"

#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <unordered_set>

#include "urbanvec/core/error.hpp"
#include "urbanvec/io/crs.hpp"
#include "urbanvec/io/raster_io.hpp"

namespace urbanvec::app {

// The adapters read files through io's readers and helpers.
using namespace urbanvec::io;

namespace {

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r\n\"");
  if (a == std::string::npos) return "";
  const size_t b = s.find_last_not_of(" \t\r\n\"");
  return s.substr(a, b - a + 1);
}

std::vector<std::string> splitCsv(const std::string& line, char separator = ',') {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string item;
  while (std::getline(ss, item, separator)) out.push_back(trim(item));
  if (!line.empty() && line.back() == separator) out.emplace_back();
  return out;
}

/// The column separator a table line seems to use: whichever of comma, semicolon and tab it holds
/// most often (comma on a tie, or when it holds none).
char detectSeparator(const std::string& line) {
  char best = ',';
  long most = std::count(line.begin(), line.end(), ',');
  for (char c : {';', '\t'}) {
    const long n = std::count(line.begin(), line.end(), c);
    if (n > most) most = n, best = c;
  }
  return best;
}

std::string separatorName(char c) {
  return c == ';' ? "semicolons" : c == '\t' ? "tabs" : "commas";
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string numberText(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

bool parseNumber(const std::string& text, double& value) {
  if (text.empty()) return false;
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return end && *end == '\0' && std::isfinite(value);
}

/// A number of a table whose columns are separated by `separator`: a table separated by semicolons
/// or tabs (as spreadsheets write in locales with a decimal comma) may write "12,5" for 12.5.
bool parseTableNumber(const std::string& text, char separator, double& value) {
  if (parseNumber(text, value)) return true;
  if (separator == ',' || std::count(text.begin(), text.end(), ',') != 1 ||
      text.find('.') != std::string::npos)
    return false;
  std::string dotted = text;
  dotted[dotted.find(',')] = '.';
  return parseNumber(dotted, value);
}

/// A missing table, or a folder given as one, is named as such rather than "cannot be opened".
void requireFile(const std::string& path, const std::string& role) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw invalidInput(role + " '" + path + "' does not exist");
  if (std::filesystem::is_directory(path, ec))
    throw invalidInput(role + " '" + path + "' is a folder, not a file");
}

/// "EPSG:32633" (or the CRS's name when it has no authority code), "no CRS" when empty.
std::string crsLabel(const std::string& wkt) {
  if (wkt.empty()) return "no CRS";
  OGRSpatialReference srs;
  if (srs.importFromWkt(wkt.c_str()) != OGRERR_NONE) return "an unreadable CRS";
  srs.AutoIdentifyEPSG();
  const char* name = srs.GetAuthorityName(nullptr);
  const char* code = srs.GetAuthorityCode(nullptr);
  if (name && code) return std::string(name) + ":" + code;
  char* proj = nullptr;
  std::string label;
  if (srs.exportToProj4(&proj) == OGRERR_NONE && proj) label = "'" + trim(proj) + "'";
  CPLFree(proj);
  if (!label.empty()) return label;
  const char* crsName = srs.GetName();
  return crsName ? "'" + std::string(crsName) + "'" : "an unnamed CRS";
}

/// "(x, y)" with enough digits for map coordinates.
std::string pair(double a, double b) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.12g, %.12g)", a, b);
  return buf;
}

/// Rasters given together must be one grid (CONVENTIONS.md "Gridded input"): the error names both
/// rasters and the first thing that differs, with both values.
void requireSameGridAs(const RasterInfo& base, const std::string& baseRole, const std::string& basePath,
                       const RasterInfo& other, const std::string& otherRole, const std::string& otherPath) {
  const GridSpec &a = base.spec, &b = other.spec;
  const std::string names = otherRole + " '" + otherPath + "' and " + baseRole + " '" + basePath + "'";
  const std::string hint = "; rasters given together must share size, geotransform and CRS";
  if (a.width != b.width || a.height != b.height)
    throw invalidInput(names + " differ in size: " + std::to_string(b.width) + "x" +
                       std::to_string(b.height) + " vs " + std::to_string(a.width) + "x" +
                       std::to_string(a.height) + " cells" + hint);
  const auto& ga = a.transform.c;
  const auto& gb = b.transform.c;
  auto same = [&](int i) { return std::fabs(ga[i] - gb[i]) <= 1e-9 * std::max(1.0, std::fabs(ga[i])); };
  if (!same(1) || !same(5))
    throw invalidInput(names + " differ in geotransform pixel size: " + pair(gb[1], gb[5]) + " vs " +
                       pair(ga[1], ga[5]) + hint);
  if (!same(2) || !same(4))
    throw invalidInput(names + " differ in geotransform rotation: " + pair(gb[2], gb[4]) + " vs " +
                       pair(ga[2], ga[4]) + hint);
  if (!same(0) || !same(3))
    throw invalidInput(names + " differ in geotransform origin: " + pair(gb[0], gb[3]) + " vs " +
                       pair(ga[0], ga[3]) + hint);
  bool sameCrs = a.crsWkt.empty() == b.crsWkt.empty();
  if (sameCrs && !a.crsWkt.empty()) {
    OGRSpatialReference sa, sb;
    sa.importFromWkt(a.crsWkt.c_str());
    sb.importFromWkt(b.crsWkt.c_str());
    sameCrs = sa.IsSame(&sb);
  }
  if (!sameCrs)
    throw invalidInput(names + " differ in CRS: " + crsLabel(b.crsWkt) + " vs " + crsLabel(a.crsWkt) + hint);
}

/// Lengths, areas and densities are in metres: a grid in degrees or feet is refused, with the
/// gdalwarp command that brings it to the UTM zone of its centre (as gridify picks).
void requireMetricGrid(const GridSpec& spec, const std::string& role, const std::string& path) {
  const std::string unit = nonMetricUnit(spec.crsWkt);
  if (unit.empty()) return;
  const auto& c = spec.transform.c;
  const double col = spec.width / 2.0, row = spec.height / 2.0;
  const int utm = utmEpsgAt(spec.crsWkt, c[0] + col * c[1] + row * c[2], c[3] + col * c[4] + row * c[5]);
  throw invalidInput(role + " '" + path + "' is in " + crsLabel(spec.crsWkt) +
                     "; vectorize needs a projected CRS in metres (the grid is in " + unit +
                     "); reproject it with gdalwarp -t_srs " +
                     (utm ? "EPSG:" + std::to_string(utm) : std::string("<a projected CRS in metres>")));
}

}  // namespace

std::vector<std::pair<double, LandUse>> readClassTable(const std::string& path, const std::string& role) {
  requireFile(path, role);
  std::ifstream f(path);
  if (!f) throw invalidInput(role + " '" + path + "' cannot be opened");
  std::vector<std::pair<double, LandUse>> table;
  std::string line;
  int lineNo = 0;
  std::optional<char> separator;  // from the first line that is not a comment
  while (std::getline(f, line)) {
    ++lineNo;
    const std::string t = trim(line);
    if (t.empty() || t[0] == '#') continue;
    const bool firstLine = !separator;
    if (!separator) separator = detectSeparator(t);
    const std::vector<std::string> cols = splitCsv(t, *separator);
    double value = 0;
    if (cols.size() < 2 || !parseTableNumber(cols[0], *separator, value)) {
      if (table.empty() && firstLine && cols.size() >= 2) continue;  // header
      throw invalidInput(role + " '" + path + "' line " + std::to_string(lineNo) +
                         " is not 'value,class_name': '" + t + "'");
    }
    const std::optional<LandUse> use = parseLandUse(cols[1]);
    if (!use)
      throw invalidInput(role + " '" + path + "' line " + std::to_string(lineNo) + " names unknown class '" +
                         cols[1] +
                         "' (expected one of unused, water, secondary_road, primary_road, residential, "
                         "commercial, industrial, park, reserved)");
    table.emplace_back(value, *use);
  }
  if (table.empty()) throw invalidInput(role + " '" + path + "' maps no value");
  return table;
}

vectorize::VectorizeInput loadGridInput(const GridInputPaths& paths, std::vector<std::string>* warnings) {
  vectorize::VectorizeInput in;
  RasterInfo info;
  const std::string luRole = "land-use raster";
  const RasterWindow* window = paths.window ? &*paths.window : nullptr;
  // With a window, the rasters are compared as wholes (before reading) and only the window is read.
  const RasterInfo fullInfo = window ? inspectRaster(paths.landUse, luRole) : RasterInfo{};
  auto checkSameGrid = [&](const std::string& path, const std::string& role) {
    if (window) requireSameGridAs(fullInfo, luRole, paths.landUse, inspectRaster(path, role), role, path);
  };
  const Grid<double> raw = readRasterBand<double>(paths.landUse, luRole, &info, window);
  const int colOffset = window ? window->xoff : 0, rowOffset = window ? window->yoff : 0;
  in.spec = info.spec;
  {
    const auto source = info.metadata.find(kRoadSourceKey);
    in.roadsFromMappedStreets = source != info.metadata.end() && source->second == kMappedStreets;
  }
  in.originCol = colOffset;
  in.originRow = rowOffset;
  if (window) {  // the whole raster's frame and transform (GridSpec::frameCol, issue 22)
    in.spec.transform = fullInfo.spec.transform;
    in.spec.frameCol = colOffset;
    in.spec.frameRow = rowOffset;
    in.spec.frameHeight = fullInfo.spec.height;
  }
  requireMetricGrid(info.spec, luRole, paths.landUse);
  if (info.spec.crsWkt.empty() && warnings)
    warnings->push_back("land-use raster '" + paths.landUse + "' has no CRS: the output layers have none");
  in.landUse = Grid<std::uint8_t>(raw.width, raw.height, 0);
  in.landUse.frameDx = in.spec.frameDx();
  in.landUse.frameDy = in.spec.frameDy();
  std::map<double, LandUse> classes;
  if (!paths.classes.empty())
    for (const auto& [v, u] : readClassTable(paths.classes)) classes[v] = u;
  for (size_t i = 0; i < raw.cells.size(); ++i) {
    const double v = raw.cells[i];
    if (info.nodata && (v == *info.nodata || (std::isnan(v) && std::isnan(*info.nodata))))
      continue;  // unused
    auto where = [&]() {
      return " at column " + std::to_string(i % raw.width + colOffset) + ", row " +
             std::to_string(i / raw.width + rowOffset);
    };
    if (!classes.empty()) {
      auto it = classes.find(v);
      if (it == classes.end())
        throw invalidInput(luRole + " '" + paths.landUse + "' holds value " + numberText(v) + where() +
                           ", which -classes table '" + paths.classes + "' does not map (add a line '" +
                           numberText(v) + ",<class name>')");
      in.landUse.cells[i] = static_cast<std::uint8_t>(it->second);
      continue;
    }
    if (std::isnan(v) || v != std::floor(v) || v < 0 || (v > 8 && v != kLandUseNodata))
      throw invalidInput(luRole + " '" + paths.landUse + "' (" + info.dataType + ") holds value " +
                         numberText(v) + where() +
                         ", which is not a land-use class code (0..8, 255 = nodata); map its values to "
                         "classes with -classes <csv>");
    in.landUse.cells[i] = static_cast<std::uint8_t>(landUseFromCode(static_cast<int>(v)));
  }

  if (!paths.density.empty()) {
    RasterInfo di;
    checkSameGrid(paths.density, "density raster");
    in.density = readRasterBand<float>(paths.density, "density raster", &di, window);
    requireSameGridAs(info, luRole, paths.landUse, di, "density raster", paths.density);
    // Nodata cells hold no one; any other value must be a population: finite and not negative.
    const std::optional<float> nodata =
        di.nodata ? std::optional<float>(static_cast<float>(*di.nodata)) : std::nullopt;
    for (size_t i = 0; i < in.density.cells.size(); ++i) {
      float& d = in.density.cells[i];
      if (nodata && (d == *nodata || (std::isnan(d) && std::isnan(*nodata)))) {
        d = 0;
        continue;
      }
      if (!std::isfinite(d) || d < 0)
        throw invalidInput("density raster '" + paths.density + "' holds value " + numberText(d) +
                           " at column " + std::to_string(i % in.density.width + colOffset) + ", row " +
                           std::to_string(i / in.density.width + rowOffset) +
                           ", which is not a population per cell (a finite number >= 0; only nodata "
                           "cells count as 0)");
    }
  }
  if (!paths.parcelTable.empty() && paths.parcels.empty())
    throw invalidInput("-parcel-table '" + paths.parcelTable +
                       "' needs the parcel raster (-parcels) that holds "
                       "the parcels' cells");
  if (!paths.parcels.empty()) {
    RasterInfo pi;
    checkSameGrid(paths.parcels, "parcels raster");
    const Grid<double> ids = readRasterBand<double>(paths.parcels, "parcels raster", &pi, window);
    requireSameGridAs(info, luRole, paths.landUse, pi, "parcels raster", paths.parcels);
    in.parcelIds = Grid<std::int32_t>(ids.width, ids.height, 0);
    for (size_t i = 0; i < ids.cells.size(); ++i) {
      const double v = ids.cells[i];
      if (pi.nodata && v == *pi.nodata) continue;
      const std::string where = " at column " + std::to_string(i % ids.width + colOffset) + ", row " +
                                std::to_string(i / ids.width + rowOffset);
      if (std::isnan(v) || v != std::floor(v) || v > 2147483647.0)
        throw invalidInput("parcels raster '" + paths.parcels + "' holds value " + numberText(v) + where +
                           ", which is not an integer parcel id");
      if (v < 0)
        throw invalidInput("parcels raster '" + paths.parcels + "' holds negative parcel id " +
                           numberText(v) + where + " (ids must be >= 0, 0 = no parcel)");
      in.parcelIds.cells[i] = static_cast<std::int32_t>(v);
    }
  }
  if (!paths.openRegions.empty()) {
    RasterInfo oi;
    const std::string role = "open-regions raster";
    checkSameGrid(paths.openRegions, role);
    const Grid<double> open = readRasterBand<double>(paths.openRegions, role, &oi, window);
    requireSameGridAs(info, luRole, paths.landUse, oi, role, paths.openRegions);
    in.openRegions = Grid<std::uint8_t>(open.width, open.height, 0);
    for (size_t i = 0; i < open.cells.size(); ++i) {
      const double v = open.cells[i];
      if (v != 0 && v != 1)
        throw invalidInput(role + " '" + paths.openRegions + "' holds value " + numberText(v) +
                           " at column " + std::to_string(i % open.width + colOffset) + ", row " +
                           std::to_string(i / open.width + rowOffset) +
                           ", which is not 0 (enclosed region) or 1 (region reaching the grid's edge)");
      in.openRegions.cells[i] = static_cast<std::uint8_t>(v);
    }
  }
  if (!paths.parcelTable.empty()) {
    requireFile(paths.parcelTable, "parcel table");
    std::ifstream f(paths.parcelTable);
    if (!f) throw invalidInput("parcel table '" + paths.parcelTable + "' cannot be opened");
    std::string line;
    if (!std::getline(f, line)) throw invalidInput("parcel table '" + paths.parcelTable + "' is empty");
    // Columns are separated by commas, or by semicolons or tabs as spreadsheets write them.
    const char separator = detectSeparator(line);
    const std::vector<std::string> header = splitCsv(line, separator);
    auto column = [&](const std::string& name) {
      for (size_t k = 0; k < header.size(); ++k)
        if (lower(header[k]) == name) return static_cast<int>(k);
      throw invalidInput("parcel table '" + paths.parcelTable + "' has no column '" + name +
                         "' (expected parcel_id,land_use,population,cells" +
                         (separator == ',' ? std::string() : ", separated by " + separatorName(separator)) +
                         ")");
    };
    const int cId = column("parcel_id"), cUse = column("land_use"), cPop = column("population"),
              cCells = column("cells");
    std::unordered_set<std::int32_t> inRaster(in.parcelIds.cells.begin(), in.parcelIds.cells.end());
    std::unordered_set<std::int32_t> seen;
    int lineNo = 1;
    while (std::getline(f, line)) {
      ++lineNo;
      if (trim(line).empty()) continue;
      const std::vector<std::string> cols = splitCsv(line, separator);
      const std::string at = "parcel table '" + paths.parcelTable + "' line " + std::to_string(lineNo);
      const int need = std::max({cId, cUse, cPop, cCells});
      if (static_cast<int>(cols.size()) <= need) {
        const char used = detectSeparator(line);
        throw invalidInput(at + " has too few columns" +
                           (used == separator
                                ? std::string()
                                : " (the header separates columns with " + separatorName(separator) +
                                      ", this line seems to use " + separatorName(used) + ")"));
      }
      double id = 0, pop = 0, cells = 0;
      if (!parseNumber(cols[cId], id) || id != std::floor(id) || id <= 0 || id > 2147483647.0)
        throw invalidInput(at + ": parcel_id '" + cols[cId] + "' is not a positive integer");
      if (!parseTableNumber(cols[cPop], separator, pop) || pop < 0)
        throw invalidInput(at + ": population '" + cols[cPop] + "' is not a number >= 0");
      if (!parseTableNumber(cols[cCells], separator, cells) || cells < 0)
        throw invalidInput(at + ": cells '" + cols[cCells] + "' is not a number >= 0");
      const std::optional<LandUse> use = parseLandUse(cols[cUse]);
      if (!use) throw invalidInput(at + ": land_use '" + cols[cUse] + "' is not a class name");
      const auto pid = static_cast<std::int32_t>(id);
      if (window && !inRaster.count(pid)) continue;  // a parcel of another window
      if (!inRaster.count(pid))
        throw invalidInput(at + " names parcel id " + std::to_string(pid) +
                           ", which is not in the parcels raster '" + paths.parcels + "'");
      if (!seen.insert(pid).second) throw invalidInput(at + " repeats parcel id " + std::to_string(pid));
      in.parcelTable.push_back({pid, *use, pop, static_cast<std::int64_t>(cells)});
    }
    std::size_t missing = 0;
    for (std::int32_t id : inRaster) missing += id > 0 && !seen.count(id);
    if (missing > 0 && warnings)
      warnings->push_back(std::to_string(missing) + " parcel ids of parcels raster '" + paths.parcels +
                          "' are not in parcel table '" + paths.parcelTable +
                          "'; their use and population are derived from the rasters");
  }
  return in;
}

}  // namespace urbanvec::app
