// `urbanvec evaluate`: measures a vector city against the truth it was gridded from (issue 2 §3).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>

#include "urbanvec/app/command.hpp"
#include "urbanvec/core/error.hpp"
#include "urbanvec/evaluate/evaluate.hpp"
#include "urbanvec/evaluate/report_format.hpp"
#include "urbanvec/io/atomic_output.hpp"
#include "urbanvec/io/crs.hpp"
#include "urbanvec/io/evaluate_input.hpp"
#include "urbanvec/io/raster_io.hpp"
#include "urbanvec/io/vector_io.hpp"

namespace urbanvec {
namespace {

using app::option;
using app::Role;
using app::ValueType;

/// One of the three layers both cities may have.
struct LayerRole {
  const char* name;  ///< "roads"
  io::GeometryKind kind;
  const char* metrics;  ///< what is absent without it
};

const LayerRole kRoles[] = {{"roads", io::GeometryKind::Lines, "road metrics"},
                            {"blocks", io::GeometryKind::Polygons, "block metrics"},
                            {"parcels", io::GeometryKind::Polygons, "parcel metrics"}};

app::CommandSpec spec() {
  const evaluate::EvaluateOptions defaults;
  app::CommandSpec s;
  s.name = "evaluate";
  s.summary = "Measures a vector city (roads, blocks, parcels) against its truth.";
  s.description =
      "Compares the layers of <result> (as written by 'urbanvec vectorize', or naive baselines such as "
      "gdal_polygonize.py polygons and GRASS r.thin + r.to.vect centrelines) with the truth.gpkg written by "
      "'urbanvec gridify', and prints a table: road centreline distances both ways (median and 95th "
      "percentile, in metres and cells, sampled every quarter cell; roads of class 'perimeter' are not "
      "roads), road turning per km relative to the truth, the share of truth blocks matched by a result "
      "block with IoU >= 0.7, and parcel counts, land-use shares, gaps, overlaps and invalid geometries. "
      "Layers that cannot be found make their metrics 'absent' (null in JSON), never 0. The result is "
      "reprojected to the truth's CRS, which must be projected in metres. The cell size comes from the "
      "truth's grid_info table unless -cell-size is given. See docs/evaluate.md.";
  s.group = "Evaluation";
  s.positionals = {
      {"result", "Vector dataset to evaluate (e.g. the output of 'urbanvec vectorize').", Role::InputVector},
      {"truth", "Truth vector dataset (truth.gpkg written by 'urbanvec gridify').", Role::InputVector}};
  s.options.push_back(
      option("-json", ValueType::String, "<file>", "Also writes the report as JSON to this file.")
          .withRole(Role::OutputFile));
  s.options.push_back(option("-overwrite", ValueType::Flag, "", "Replace the -json output if it exists."));
  s.options.push_back(option("-cell-size", ValueType::Real, "<metres>",
                             "Cell size of the grid; overrides the cell_size of the truth's grid_info table.")
                          .withUnit("m")
                          .atLeast(1e-6));
  for (const LayerRole& r : kRoles) {
    const std::string n = r.name;
    s.options.push_back(
        option("-" + n + "-layer", ValueType::String, "<name>", "Layer of the result holding the " + n + ".")
            .byDefault(n));
    s.options.push_back(option("-" + n + "-from", ValueType::String, "<dataset>",
                               "Reads the result " + n + " from this dataset instead of <result>.")
                            .withRole(Role::InputVector)
                            .isAdvanced());
    s.options.push_back(
        option("-" + n + "-where", ValueType::String, "<OGR SQL where>",
               "Keeps only the result " + n + " matching this attribute filter (as ogr2ogr -where).")
            .isAdvanced());
  }
  s.options.push_back(option("-landuse", ValueType::String, "<landuse.tif>",
                             "Land-use grid the truth was rasterised on; it tells which truth blocks can "
                             "be matched at all (at least -matchable-share of their area on land cells). "
                             "Default: landuse.tif beside the truth when it exists; 'none' leaves the "
                             "matchable share out.")
                          .withRole(Role::InputRaster));
  s.options.push_back(option("-matchable-share", ValueType::Real, "<ratio>",
                             "Share of a truth block's area on land cells from which it counts as "
                             "matchable.")
                          .byDefault(app::numberText(defaults.matchableLandShare))
                          .atLeast(0)
                          .atMost(1)
                          .isAdvanced());
  s.options.push_back(
      option("-landuse-field", ValueType::String, "<name>",
             "Field of the result parcels holding the land use: a class name or a class code of "
             "landuse.tif (e.g. DN of gdal_polygonize.py).")
          .byDefault(defaults.resultLandUseField)
          .isAdvanced());
  s.options.push_back(option("-min-iou", ValueType::Real, "<ratio>",
                             "Smallest intersection over union for a truth block to count as matched.")
                          .byDefault(app::numberText(defaults.blockMatchIoU))
                          .atLeast(1e-6)
                          .atMost(1)
                          .isAdvanced());
  s.options.push_back(option("-min-block-cells", ValueType::Real, "<cells>",
                             "Truth blocks smaller than this are left out of the block matching.")
                          .byDefault(app::numberText(defaults.minTruthBlockCells))
                          .withUnit("cells")
                          .atLeast(0)
                          .isAdvanced());
  s.options.push_back(option("-sample-spacing", ValueType::Real, "<cells>",
                             "Spacing of the points sampled along road centrelines for the distances.")
                          .byDefault(app::numberText(defaults.sampleSpacingCells))
                          .withUnit("cells")
                          .atLeast(1e-3)
                          .isAdvanced());
  s.options.push_back(option("-network-snap", ValueType::Real, "<cells>",
                             "Road ends closer than this join when the networks are noded for their "
                             "intersection, dead-end and component counts (0 = exact).")
                          .byDefault(app::numberText(defaults.networkSnapCells))
                          .withUnit("cells")
                          .atLeast(0)
                          .atMost(1)
                          .isAdvanced());
  s.examples = {
      "urbanvec evaluate -json report.json city.gpkg sample_data/monaco/truth.gpkg",
      "urbanvec evaluate -roads-from grass_centrelines.gpkg -blocks-layer out -blocks-where \"DN >= 4\" "
      "-parcels-layer out -parcels-where \"DN >= 4\" -landuse-field DN polygonized.gpkg truth.gpkg"};
  return s;
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out.empty() ? "none" : out;
}

std::string describe(const std::string& layer, const std::string& path, const std::string& where) {
  return "'" + layer + "' of '" + path + "'" + (where.empty() ? "" : " where " + where);
}

void run(const app::ParsedArgs& args, app::CommandContext& ctx) {
  const std::string resultPath = args.positionals()[0];
  const std::string truthPath = args.positionals()[1];
  std::optional<io::AtomicOutput> json;
  if (args.given("-json"))
    json.emplace(args.str("-json"), io::OutputRules{args.flag("-overwrite"), false, {}, ctx.inputs});

  io::listEvaluationLayers(truthPath, "truth");
  const std::vector<std::string> resultLayers = io::listEvaluationLayers(resultPath, "result");
  for (const LayerRole& r : kRoles)
    if (args.given(std::string("-") + r.name + "-from"))
      io::listEvaluationLayers(args.str(std::string("-") + r.name + "-from"),
                               std::string("result ") + r.name);

  double cellSize = 0.0;
  if (args.given("-cell-size")) {
    cellSize = args.real("-cell-size");
  } else if (const std::optional<double> fromTruth = io::readGridInfoCellSize(truthPath)) {
    cellSize = *fromTruth;
  } else {
    throw invalidInput("truth '" + truthPath +
                       "' has no grid_info table giving the cell size; give -cell-size <metres>");
  }
  reportProgress(ctx.progress, 0.05, "reading");

  evaluate::EvaluationInput input;
  input.cellSize = cellSize;
  evaluate::ReportInputs labels;
  labels.result = resultPath;
  labels.truth = truthPath;
  std::optional<Layer>* truthSlots[] = {&input.truth.roads, &input.truth.blocks, &input.truth.parcels};
  std::optional<Layer>* resultSlots[] = {&input.result.roads, &input.result.blocks, &input.result.parcels};
  std::string* truthLabels[] = {&labels.truthRoads, &labels.truthBlocks, &labels.truthParcels};
  std::string* resultLabels[] = {&labels.resultRoads, &labels.resultBlocks, &labels.resultParcels};

  // The truth's CRS is the frame of every measure: the first truth layer's, the others brought to it.
  std::string truthCrs;
  for (int i = 0; i < 3; ++i) {
    const LayerRole& r = kRoles[i];
    const std::string role = std::string("truth ") + r.name;
    io::VectorReadOptions toFirst;
    toFirst.targetCrs = truthCrs;
    std::optional<io::LayerRead> read =
        io::readEvaluationLayer(truthPath, r.name, "", "", r.kind, role, toFirst);
    if (!read) continue;
    if (truthCrs.empty()) {
      truthCrs = read->crsWkt;
      if (!io::isProjectedInMetres(truthCrs))
        throw invalidInput("truth '" + truthPath + "' is in " + io::crsShortName(truthCrs) +
                           ", not a projected CRS in metres; reproject it with ogr2ogr -t_srs");
    }
    *truthSlots[i] = std::move(read->layer);
    *truthLabels[i] = describe(r.name, truthPath, "");
    reportProgress(ctx.progress, 0.05 + 0.04 * (i + 1), "reading");
  }
  if (truthCrs.empty()) {
    const std::vector<std::string> names = io::listEvaluationLayers(truthPath, "truth");
    throw invalidInput("truth '" + truthPath +
                       "' has none of the layers roads, blocks, parcels (its layers: " + joined(names) + ")");
  }

  io::VectorReadOptions toTruth;
  toTruth.targetCrs = truthCrs;
  for (int i = 0; i < 3; ++i) {
    const LayerRole& r = kRoles[i];
    const std::string prefix = std::string("-") + r.name;
    const std::string path = args.given(prefix + "-from") ? args.str(prefix + "-from") : resultPath;
    const std::string layerName = args.str(prefix + "-layer");
    const std::string where = args.given(prefix + "-where") ? args.str(prefix + "-where") : "";
    const std::string role = std::string("result ") + r.name;
    std::optional<io::LayerRead> read =
        io::readEvaluationLayer(path, layerName, where, prefix + "-where", r.kind, role, toTruth);
    if (!read) {
      const std::vector<std::string> names =
          path == resultPath ? resultLayers : io::listEvaluationLayers(path, role);
      ctx.warn("'" + path + "' has no layer '" + layerName + "' (its layers: " + joined(names) + "); " +
               r.metrics + " are absent (choose a layer with " + prefix + "-layer)");
      continue;
    }
    *resultSlots[i] = std::move(read->layer);
    *resultLabels[i] = describe(layerName, path, where);
    reportProgress(ctx.progress, 0.17 + 0.04 * (i + 1), "reading");
  }

  // The land-use grid: given, or landuse.tif beside the truth (as gridify writes them).
  std::string landUsePath;
  if (args.given("-landuse")) {
    if (args.str("-landuse") != "none") landUsePath = args.str("-landuse");
  } else {
    const std::filesystem::path beside = std::filesystem::path(truthPath).parent_path() / "landuse.tif";
    std::error_code ec;
    if (std::filesystem::is_regular_file(beside, ec)) landUsePath = beside.string();
  }
  if (!landUsePath.empty()) {
    io::RasterInfo info;
    evaluate::LandUseCells cells;
    cells.codes = io::readRasterBand<std::uint8_t>(landUsePath, "land-use grid", &info);
    cells.spec = info.spec;
    if (!info.spec.crsWkt.empty() && io::crsShortName(info.spec.crsWkt) != io::crsShortName(truthCrs))
      ctx.warn("the land-use grid '" + landUsePath + "' is in " + io::crsShortName(info.spec.crsWkt) +
               ", the truth in " + io::crsShortName(truthCrs) + "; the matchable block share is absent");
    else
      input.landUse = std::move(cells);
  }

  evaluate::EvaluateOptions options;
  options.matchableLandShare = args.real("-matchable-share");
  options.resultLandUseField = args.str("-landuse-field");
  if (input.result.parcels && input.truth.parcels &&
      input.result.parcels->fieldIndex(options.resultLandUseField) < 0)
    ctx.warn("the result parcels (" + labels.resultParcels + ") have no field '" +
             options.resultLandUseField +
             "'; the land-use share error is absent (choose a field with -landuse-field)");
  if (input.result.parcels && input.truth.parcels &&
      input.truth.parcels->fieldIndex(options.truthLandUseField) < 0)
    ctx.warn("the truth parcels (" + labels.truthParcels + ") have no field '" + options.truthLandUseField +
             "'; the land-use share error is absent");
  options.blockMatchIoU = args.real("-min-iou");
  options.minTruthBlockCells = args.real("-min-block-cells");
  options.sampleSpacingCells = args.real("-sample-spacing");
  options.networkSnapCells = args.real("-network-snap");
  const evaluate::EvaluationReport report =
      evaluate::evaluate(input, options, subProgress(ctx.progress, 0.3, 1.0));
  if (!report.layersOverlap)
    ctx.warn("the result '" + resultPath + "' (" + evaluate::formatExtent(*report.resultExtent) +
             ") and the truth '" + truthPath + "' (" + evaluate::formatExtent(*report.truthExtent) +
             ") do not overlap in " + io::crsShortName(truthCrs) +
             ": the distances and matches measure how far apart they lie, not the result; check that both "
             "carry the right CRS");
  reportProgress(ctx.progress, 1.0, "done");

  if (json) {
    {
      std::ofstream out(json->tempPath(), std::ios::binary);
      out << evaluate::formatReportJson(report, labels);
      out.flush();
      if (!out) throw ioError("cannot write -json output '" + json->path() + "'");
    }
    json->commit(ctx.progress);
  }
  std::fflush(stdout);
  *ctx.out << evaluate::formatReportTable(report, labels) << std::flush;
}

const bool registered = app::registerCommand(spec(), run);

}  // namespace
}  // namespace urbanvec
