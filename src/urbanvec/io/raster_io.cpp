#include "urbanvec/io/raster_io.hpp"

#include <cpl_string.h>
#include <gdal_priv.h>
#include <gdal_utils.h>
#include <ogr_spatialref.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "urbanvec/core/error.hpp"
#include "urbanvec/io/creation_options.hpp"
#include "urbanvec/io/gdal_init.hpp"
#include "urbanvec/io/gdal_types.hpp"

namespace urbanvec::io {

namespace {

DatasetPtr openRaster(const std::string& path, const std::string& role) {
  ensureGdal();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec) && path.rfind("/vsi", 0) != 0)
    throw invalidInput(role + " '" + path + "' does not exist");
  CPLErrorReset();
  DatasetPtr ds(static_cast<GDALDataset*>(
      GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
  if (!ds) {
    std::string why = lastGdalMessage();
    throw invalidInput(role + " '" + path + "' is not a raster GDAL can read" +
                       (why.empty() ? "" : " (" + why + ")"));
  }
  if (ds->GetRasterCount() < 1) throw invalidInput(role + " '" + path + "' has no raster band");
  return ds;
}

RasterInfo describe(GDALDataset& ds) {
  RasterInfo info;
  info.spec.width = ds.GetRasterXSize();
  info.spec.height = ds.GetRasterYSize();
  double gt[6];
  if (ds.GetGeoTransform(gt) == CE_None)
    for (int i = 0; i < 6; ++i) info.spec.transform.c[i] = gt[i];
  if (const OGRSpatialReference* srs = ds.GetSpatialRef()) {
    char* wkt = nullptr;
    const char* opts[] = {"FORMAT=WKT2_2019", nullptr};
    if (srs->exportToWkt(&wkt, opts) == OGRERR_NONE && wkt) info.spec.crsWkt = wkt;
    CPLFree(wkt);
  }
  GDALRasterBand* band = ds.GetRasterBand(1);
  info.dataType = GDALGetDataTypeName(band->GetRasterDataType());
  int hasNodata = 0;
  const double nd = band->GetNoDataValue(&hasNodata);
  if (hasNodata) info.nodata = nd;
  info.bandCount = ds.GetRasterCount();
  for (char** item = ds.GetMetadata(); item && *item; ++item) {
    char* key = nullptr;
    const char* value = CPLParseNameValue(*item, &key);
    if (key && value) info.metadata[key] = value;
    CPLFree(key);
  }
  return info;
}

template <class T>
constexpr GDALDataType gdalType();
template <>
constexpr GDALDataType gdalType<std::uint8_t>() {
  return GDT_Byte;
}
template <>
constexpr GDALDataType gdalType<std::int32_t>() {
  return GDT_Int32;
}
template <>
constexpr GDALDataType gdalType<float>() {
  return GDT_Float32;
}
template <>
constexpr GDALDataType gdalType<double>() {
  return GDT_Float64;
}

}  // namespace

RasterInfo inspectRaster(const std::string& path, const std::string& role) {
  DatasetPtr ds = openRaster(path, role);
  return describe(*ds);
}

GridSpec windowSpec(const GridSpec& full, const RasterWindow& w, const std::string& role,
                    const std::string& path) {
  const std::string text = std::to_string(w.xoff) + " " + std::to_string(w.yoff) + " " +
                           std::to_string(w.xsize) + " " + std::to_string(w.ysize);
  if (w.xsize <= 0 || w.ysize <= 0)
    throw invalidOption("-srcwin " + text + ": the window size must be at least 1 x 1 cells");
  if (w.xoff < 0 || w.yoff < 0 || static_cast<long long>(w.xoff) + w.xsize > full.width ||
      static_cast<long long>(w.yoff) + w.ysize > full.height)
    throw invalidOption("-srcwin " + text + " is not inside " + role + " '" + path + "' (" +
                        std::to_string(full.width) + " x " + std::to_string(full.height) +
                        " cells; the window must lie within columns 0.." + std::to_string(full.width - 1) +
                        " and rows 0.." + std::to_string(full.height - 1) + ")");
  GridSpec spec = full;
  spec.width = w.xsize;
  spec.height = w.ysize;
  auto& c = spec.transform.c;
  const auto& f = full.transform.c;
  c[0] = f[0] + w.xoff * f[1] + w.yoff * f[2];
  c[3] = f[3] + w.xoff * f[4] + w.yoff * f[5];
  return spec;
}

template <class T>
Grid<T> readRasterBand(const std::string& path, const std::string& role, RasterInfo* infoOut,
                       const RasterWindow* window) {
  DatasetPtr ds = openRaster(path, role);
  RasterInfo info = describe(*ds);
  if (info.spec.width <= 0 || info.spec.height <= 0)
    throw invalidInput(role + " '" + path + "' has no cells");
  RasterWindow w{0, 0, info.spec.width, info.spec.height};
  if (window) {
    info.spec = windowSpec(info.spec, *window, role, path);
    w = *window;
  }
  Grid<T> grid(info.spec.width, info.spec.height);
  CPLErrorReset();
  if (ds->GetRasterBand(1)->RasterIO(GF_Read, w.xoff, w.yoff, grid.width, grid.height, grid.cells.data(),
                                     grid.width, grid.height, gdalType<T>(), 0, 0) != CE_None)
    throw invalidInput(role + " '" + path + "' could not be read (" + lastGdalMessage() + ")");
  if (infoOut) *infoOut = info;
  return grid;
}

Grid<double> warpRasterBand(const std::string& path, const std::string& role, const GridSpec& target,
                            const std::string& resampling, RasterInfo* infoOut) {
  DatasetPtr ds = openRaster(path, role);
  const RasterInfo info = describe(*ds);
  double gt[6];
  if (ds->GetGeoTransform(gt) != CE_None)
    throw invalidInput(role + " '" + path +
                       "' has no georeferencing (geotransform), so it cannot be placed on the grid");
  if (info.spec.crsWkt.empty())
    throw invalidInput(
        role + " '" + path +
        "' has no CRS, so it cannot be placed on the grid; give it one with gdal_edit -a_srs <crs>");
  const auto& c = target.transform.c;
  if (c[2] != 0.0 || c[4] != 0.0 || !(c[1] > 0.0) || !(c[5] < 0.0))
    throw internalError("warpRasterBand: the target grid is not north-up");
  const auto text = [](double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return std::string(buf);
  };
  CPLStringList args;
  for (const std::string& a : {std::string("-of"),
                               std::string("MEM"),
                               std::string("-t_srs"),
                               target.crsWkt,
                               std::string("-te"),
                               text(c[0]),
                               text(c[3] + target.height * c[5]),
                               text(c[0] + target.width * c[1]),
                               text(c[3]),
                               std::string("-ts"),
                               std::to_string(target.width),
                               std::to_string(target.height),
                               std::string("-r"),
                               resampling,
                               std::string("-ot"),
                               std::string("Float64"),
                               std::string("-dstnodata"),
                               std::string("nan"),
                               std::string("-wo"),
                               std::string("INIT_DEST=NO_DATA")})
    args.AddString(a.c_str());
  CPLErrorReset();
  GDALWarpAppOptions* options = GDALWarpAppOptionsNew(args.List(), nullptr);
  if (!options) throw internalError(std::string("gdalwarp options refused (") + lastGdalMessage() + ")");
  GDALDatasetH source = ds.get();
  int usageError = 0;
  DatasetPtr warped(static_cast<GDALDataset*>(GDALWarp("", nullptr, 1, &source, options, &usageError)));
  GDALWarpAppOptionsFree(options);
  if (!warped)
    throw invalidInput(role + " '" + path + "' could not be warped onto the grid (" + lastGdalMessage() +
                       ")");
  Grid<double> grid(target.width, target.height);
  if (warped->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, grid.width, grid.height, grid.cells.data(),
                                         grid.width, grid.height, GDT_Float64, 0, 0) != CE_None)
    throw invalidInput(role + " '" + path + "' could not be read (" + lastGdalMessage() + ")");
  if (infoOut) *infoOut = info;
  return grid;
}

template <class T>
void writeRasterBand(const std::string& path, const GridSpec& spec, const Grid<T>& grid,
                     std::optional<double> nodata, const RasterWriteOptions& options) {
  ensureGdal();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(options.format.c_str());
  if (!driver) throw invalidOption("-of: unknown raster format '" + options.format + "'");
  CPLStringList co;
  for (const std::string& kv : options.creationOptions) co.AddString(kv.c_str());
  if (options.format == "GTiff" && co.FetchNameValue("COMPRESS") == nullptr)
    co.SetNameValue("COMPRESS", "DEFLATE");
  CPLErrorReset();
  DatasetPtr ds(driver->Create(path.c_str(), grid.width, grid.height, 1, gdalType<T>(), co.List()));
  if (!ds) throw ioError("cannot create raster '" + path + "' (" + lastGdalMessage() + ")");
  double gt[6];
  for (int i = 0; i < 6; ++i) gt[i] = spec.transform.c[i];
  ds->SetGeoTransform(gt);
  if (!spec.crsWkt.empty()) {
    OGRSpatialReference srs;
    if (srs.importFromWkt(spec.crsWkt.c_str()) == OGRERR_NONE) ds->SetSpatialRef(&srs);
  }
  for (const auto& [key, value] : options.metadata) ds->SetMetadataItem(key.c_str(), value.c_str());
  GDALRasterBand* band = ds->GetRasterBand(1);
  if (nodata) band->SetNoDataValue(*nodata);
  if (band->RasterIO(GF_Write, 0, 0, grid.width, grid.height, const_cast<T*>(grid.cells.data()), grid.width,
                     grid.height, gdalType<T>(), 0, 0) != CE_None)
    throw ioError("cannot write raster '" + path + "' (" + lastGdalMessage() + ")");
  CPLErrorReset();
  GDALClose(ds.release());
  if (CPLGetLastErrorType() >= CE_Failure)
    throw ioError("cannot finish raster '" + path + "' (" + lastGdalMessage() + ")");
}

void checkRasterWriteOptions(const RasterWriteOptions& options) {
  ensureGdal();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(options.format.c_str());
  if (!driver || !driver->GetMetadataItem(GDAL_DCAP_RASTER) || !driver->GetMetadataItem(GDAL_DCAP_CREATE))
    throw invalidOption("-of: '" + options.format + "' is not a raster format GDAL can write");
  checkCreationOptions(driver->GetMetadataItem(GDAL_DMD_CREATIONOPTIONLIST), options.creationOptions, "-co",
                       "raster", options.format);
}

void requireSameGrid(const GridSpec& a, const std::string& aPath, const GridSpec& b,
                     const std::string& bPath) {
  const std::string both = "'" + bPath + "' and '" + aPath + "'";
  if (a.width != b.width || a.height != b.height)
    throw invalidInput(both + " differ in size (" + std::to_string(b.width) + "x" + std::to_string(b.height) +
                       " vs " + std::to_string(a.width) + "x" + std::to_string(a.height) + " cells)");
  for (int i = 0; i < 6; ++i) {
    const double tol = 1e-9 * std::max(1.0, std::fabs(a.transform.c[i]));
    if (std::fabs(a.transform.c[i] - b.transform.c[i]) > tol)
      throw invalidInput(both + " differ in geotransform");
  }
  if (a.crsWkt.empty() != b.crsWkt.empty()) throw invalidInput(both + " differ in CRS");
  if (!a.crsWkt.empty()) {
    OGRSpatialReference sa, sb;
    sa.importFromWkt(a.crsWkt.c_str());
    sb.importFromWkt(b.crsWkt.c_str());
    if (!sa.IsSame(&sb)) throw invalidInput(both + " differ in CRS");
  }
}

template Grid<std::uint8_t> readRasterBand(const std::string&, const std::string&, RasterInfo*,
                                           const RasterWindow*);
template Grid<std::int32_t> readRasterBand(const std::string&, const std::string&, RasterInfo*,
                                           const RasterWindow*);
template Grid<float> readRasterBand(const std::string&, const std::string&, RasterInfo*, const RasterWindow*);
template Grid<double> readRasterBand(const std::string&, const std::string&, RasterInfo*,
                                     const RasterWindow*);
template void writeRasterBand(const std::string&, const GridSpec&, const Grid<std::uint8_t>&,
                              std::optional<double>, const RasterWriteOptions&);
template void writeRasterBand(const std::string&, const GridSpec&, const Grid<std::int32_t>&,
                              std::optional<double>, const RasterWriteOptions&);
template void writeRasterBand(const std::string&, const GridSpec&, const Grid<float>&, std::optional<double>,
                              const RasterWriteOptions&);
template void writeRasterBand(const std::string&, const GridSpec&, const Grid<double>&, std::optional<double>,
                              const RasterWriteOptions&);

}  // namespace urbanvec::io
