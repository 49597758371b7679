// `urbanvec gridify`: real city vectors -> gridded input (issue 2 §2; docs/gridify.md).
#include <array>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "urbanvec/app/city_source.hpp"
#include "urbanvec/app/command.hpp"
#include "urbanvec/app/grid_input.hpp"
#include "urbanvec/app/land_cover.hpp"
#include "urbanvec/core/error.hpp"
#include "urbanvec/gridify/gridify.hpp"
#include "urbanvec/io/atomic_output.hpp"
#include "urbanvec/io/crs.hpp"
#include "urbanvec/io/raster_io.hpp"
#include "urbanvec/io/vector_io.hpp"

namespace urbanvec {
namespace {

using app::option;
using app::Role;
using app::ValueType;

app::CommandSpec spec() {
  app::CommandSpec s;
  s.name = "gridify";
  s.summary =
      "Turns real city vectors (OpenStreetMap, GeoPackage, shapefile) into the gridded input of vectorize.";
  s.description =
      "Reads roads, land use, buildings, water (and the sea side of an OSM coastline) and optional parcels "
      "from any "
      "OGR source, and writes landuse.tif, density.tif, parcels.tif, parcels.csv and truth.gpkg (roads, "
      "blocks, "
      "parcels, water, grid_info) into <output_dir>. Secondary roads are rasterized 1 cell wide and primary "
      "roads 2 "
      "cells wide, both 4-connected. OSM files are read through GDAL's OSM driver (layers lines and "
      "multipolygons); other sources name their layers with -roads-layer, -buildings-layer, -parcels-layer, "
      "-landuse-layer, -water-layer. See docs/gridify.md for the class mapping and every rule.";
  s.group = "Gridded input";
  s.positionals = {
      {"input", "City vectors: .osm/.pbf, GeoPackage, shapefile or any OGR source.", Role::InputVector},
      {"output_dir",
       "Folder to write the grid and truth.gpkg into (created when missing; other files in it are kept).",
       Role::OutputFolder}};
  auto& o = s.options;
  o.push_back(option("-tr", ValueType::Real, "<metres>", "Cell size.").byDefault("12").withUnit("m"));
  o.push_back(
      option("-te", ValueType::Real, "<xmin> <ymin> <xmax> <ymax>",
             "Grid extent in the grid CRS; default: the extent of the roads, buildings and land-use areas, "
             "snapped outwards to whole cells.")
          .values(4)
          .withUnit("m"));
  o.push_back(
      option("-t_srs", ValueType::String, "<crs>",
             "Grid CRS (projected, metres); default: the UTM zone of the data's centre when the input is "
             "geographic, else the input CRS.")
          .withRole(Role::Crs));
  o.push_back(option("-a_srs", ValueType::String, "<crs>",
                     "CRS of an input that carries none (overrides the input's).")
                  .withRole(Role::Crs));
  o.push_back(option("-roads-layer", ValueType::String, "<layer>",
                     "Roads layer of a non-OSM input; default roads or streets."));
  o.push_back(option("-buildings-layer", ValueType::String, "<layer>",
                     "Buildings layer of a non-OSM input; default buildings."));
  o.push_back(
      option("-parcels-layer", ValueType::String, "<layer>",
             "Layer of real parcels; without it parcels are a building-based tessellation of the blocks."));
  o.push_back(option("-landuse-layer", ValueType::String, "<layer>",
                     "Land-use polygons of a non-OSM input; default landuse."));
  o.push_back(option("-water-layer", ValueType::String, "<layer>",
                     "Water polygons of a non-OSM input; default water."));
  o.push_back(option("-road-class-field", ValueType::String, "<field>",
                     "Field with OSM highway values; a roads layer without it is all of -default-road-class.")
                  .byDefault("highway"));
  o.push_back(option("-default-road-class", ValueType::Choice, "<class>",
                     "Class of roads in a layer without the road class field.")
                  .oneOf({"secondary", "primary"})
                  .byDefault("secondary"));
  o.push_back(option("-primary-highways", ValueType::String, "<list>",
                     "Comma-separated highway values rasterized as primary roads.")
                  .byDefault("motorway,motorway_link,trunk,trunk_link,primary,primary_link")
                  .isAdvanced());
  o.push_back(
      option("-secondary-highways", ValueType::String, "<list>",
             "Comma-separated highway values rasterized as secondary roads.")
          .byDefault("secondary,secondary_link,tertiary,tertiary_link,unclassified,residential,living_street")
          .isAdvanced());
  o.push_back(
      option("-service-roads", ValueType::Flag, "", "Also rasterize highway=service as secondary roads."));
  o.push_back(
      option("-landuse-field", ValueType::String, "<field>",
             "Field with a class name or landuse/building value in land-use, building and parcel layers."));
  o.push_back(option("-population-field", ValueType::String, "<field>",
                     "Parcel field with the population; default: estimated from buildings."));
  o.push_back(
      option("-levels-field", ValueType::String, "<field>", "Building field with the number of storeys.")
          .byDefault("building:levels")
          .isAdvanced());
  o.push_back(
      option("-default-levels", ValueType::Real, "<storeys>", "Storeys of a building whose count is unknown.")
          .byDefault("3")
          .atLeast(0.1));
  o.push_back(option("-floor-area-per-person", ValueType::Real, "<m2>",
                     "Residential floor area per inhabitant, for the population estimate.")
                  .byDefault("40")
                  .withUnit("m2")
                  .atLeast(1));
  o.push_back(option("-parcel-reach", ValueType::Real, "<metres>",
                     "Derived parcels reach at most this far from their building.")
                  .byDefault("50")
                  .withUnit("m")
                  .atLeast(0)
                  .isAdvanced());
  o.push_back(option("-truth-curb-primary", ValueType::Real, "<cells>",
                     "Truth blocks end this far from a primary road's centreline (its half width).")
                  .byDefault(app::numberText(gridify::GridifyOptions{}.truthCurbPrimaryCells))
                  .withUnit("cells")
                  .atLeast(0)
                  .isAdvanced());
  o.push_back(option("-truth-curb-secondary", ValueType::Real, "<cells>",
                     "Truth blocks end this far from a secondary road's centreline (its half width).")
                  .byDefault(app::numberText(gridify::GridifyOptions{}.truthCurbSecondaryCells))
                  .withUnit("cells")
                  .atLeast(0)
                  .isAdvanced());
  o.push_back(option("-truth-road-reach", ValueType::Real, "<cells>",
                     "Truth roads keep the pieces of their centrelines this close to a road cell's centre.")
                  .byDefault(app::numberText(gridify::GridifyOptions{}.truthRoadReachCells))
                  .withUnit("cells")
                  .atLeast(0.71)
                  .isAdvanced());
  const gridify::UntaggedLandOptions untagged;
  o.push_back(option("-no-infer-use", ValueType::Flag, "",
                     "Leave land no land-use polygon covers unused (default: blocks inside the street "
                     "network take the use of their buildings, else of their streets, else -default-use)."));
  o.push_back(option("-default-use", ValueType::Choice, "<class>",
                     "Use of an untagged block inside the street network with no building and no telling "
                     "street; unused leaves it empty.")
                  .oneOf({"residential", "commercial", "industrial", "park", "reserved", "unused"})
                  .byDefault(std::string(landUseName(untagged.defaultUse))));
  o.push_back(
      option("-untagged-share", ValueType::Real, "<ratio>",
             "A block is untagged when at most this share of its cells lies under a land-use polygon.")
          .byDefault(app::numberText(untagged.maxTaggedShare))
          .atLeast(0)
          .atMost(1)
          .isAdvanced());
  o.push_back(option("-street-use", ValueType::String, "<highway=class,...>",
                     "Street classes and the use of the untagged blocks they bound (at least half of a "
                     "block's street length decides).")
                  .byDefault("residential=residential,living_street=residential")
                  .isAdvanced());
  o.push_back(option("-landcover", ValueType::String, "<raster>",
                     "A land-cover raster (any CRS, band 1), warped onto the grid with mode resampling: its "
                     "developed classes claim land no land-use polygon covers (needs -landcover-table).")
                  .withRole(Role::InputRaster));
  o.push_back(option("-landcover-table", ValueType::String, "<csv>",
                     "value,class_name lines mapping every value of the -landcover raster to a class "
                     "(unused, water and road classes claim nothing).")
                  .withRole(Role::InputFile));
  for (const app::OptionSpec& r : app::rasterOutputOptions()) o.push_back(r);
  s.examples = {"urbanvec gridify -tr 8 monaco.osm.pbf monaco_grid",
                "urbanvec gridify -tr 6 -t_srs EPSG:32633 -roads-layer streets -buildings-layer buildings "
                "-parcels-layer plots "
                "bubenec.gpkg bubenec_grid"};
  s.outputLayers = {"roads", "blocks", "parcels", "water", "grid_info"};
  return s;
}

/// Every file gridify writes into its output folder.
constexpr std::array<const char*, 5> kOutputFiles = {"landuse.tif", "density.tif", "parcels.tif",
                                                     "parcels.csv", "truth.gpkg"};

std::vector<std::string> splitList(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

void writeParcelsCsv(const std::string& path, const std::vector<gridify::ParcelRecord>& parcels) {
  std::ofstream out(path);
  out << "parcel_id,land_use,population,cells\n";
  out.precision(10);
  for (const gridify::ParcelRecord& p : parcels)
    out << p.id << ',' << landUseName(p.use) << ',' << p.population << ',' << p.cells << '\n';
  if (!out) throw ioError("cannot write '" + path + "'");
}

void run(const app::ParsedArgs& args, app::CommandContext& ctx) {
  const std::string input = args.positionals()[0];
  const std::string outputDir = args.positionals()[1];
  const auto start = std::chrono::steady_clock::now();

  gridify::GridifyOptions options;
  options.cellSize = args.real("-tr");
  if (!(options.cellSize > 0.0))
    throw invalidOption("-tr: the cell size must be a positive number of metres, got " + args.str("-tr"));
  if (args.given("-te")) {
    const std::vector<std::string> v = args.values("-te");
    gridify::Extent e{std::stod(v[0]), std::stod(v[1]), std::stod(v[2]), std::stod(v[3])};
    if (!(e.maxX > e.minX) || !(e.maxY > e.minY))
      throw invalidOption("-te: xmax must exceed xmin and ymax exceed ymin, got " + v[0] + " " + v[1] + " " +
                          v[2] + " " + v[3]);
    options.extent = e;
  }
  options.defaultLevels = args.real("-default-levels");
  options.floorAreaPerPerson = args.real("-floor-area-per-person");
  options.parcelReach = args.real("-parcel-reach");
  options.truthCurbPrimaryCells = args.real("-truth-curb-primary");
  options.truthCurbSecondaryCells = args.real("-truth-curb-secondary");
  options.truthRoadReachCells = args.real("-truth-road-reach");
  options.untagged.enabled = !args.flag("-no-infer-use");
  options.untagged.defaultUse = *parseLandUse(args.str("-default-use"));
  options.untagged.maxTaggedShare = args.real("-untagged-share");
  options.untagged.streetUses.clear();
  {
    std::stringstream list(args.str("-street-use"));
    std::string item;
    while (std::getline(list, item, ',')) {
      const std::size_t eq = item.find('=');
      const std::optional<LandUse> use =
          eq == std::string::npos ? std::nullopt : parseLandUse(item.substr(eq + 1));
      if (!use || eq == 0)
        throw invalidOption("-street-use takes highway=class pairs separated by commas, got '" + item + "'");
      options.untagged.streetUses.push_back({item.substr(0, eq), *use});
    }
  }

  app::LandCoverSource landCover;
  if (args.given("-landcover") != args.given("-landcover-table"))
    throw invalidOption(args.given("-landcover")
                            ? "-landcover needs -landcover-table, the value,class_name table of its values"
                            : "-landcover-table needs -landcover, the land-cover raster it describes");
  if (args.given("-landcover")) {
    landCover.raster = args.str("-landcover");
    landCover.table = args.str("-landcover-table");
    app::readClassTable(landCover.table, "-landcover-table");  // a bad table fails before any reading
  }

  app::CitySourceOptions source;
  if (args.given("-a_srs")) source.assignedCrs = args.str("-a_srs");
  if (args.given("-t_srs")) source.targetCrs = args.str("-t_srs");
  if (args.given("-roads-layer")) source.roadsLayer = args.str("-roads-layer");
  if (args.given("-buildings-layer")) source.buildingsLayer = args.str("-buildings-layer");
  if (args.given("-parcels-layer")) source.parcelsLayer = args.str("-parcels-layer");
  if (args.given("-landuse-layer")) source.landuseLayer = args.str("-landuse-layer");
  if (args.given("-water-layer")) source.waterLayer = args.str("-water-layer");
  if (args.given("-landuse-field")) source.landuseField = args.str("-landuse-field");
  if (args.given("-population-field")) source.populationField = args.str("-population-field");
  source.roadClassField = args.str("-road-class-field");
  source.levelsField = args.str("-levels-field");
  source.defaultRoadClass =
      args.str("-default-road-class") == "primary" ? LandUse::PrimaryRoad : LandUse::SecondaryRoad;
  source.roadClasses.primary = splitList(args.str("-primary-highways"));
  source.roadClasses.secondary = splitList(args.str("-secondary-highways"));
  if (args.flag("-service-roads")) source.roadClasses.secondary.push_back("service");
  if (args.given("-t_srs")) io::crsToWkt(source.targetCrs, "-t_srs");  // a bad CRS fails before any reading
  if (args.given("-a_srs")) io::crsToWkt(source.assignedCrs, "-a_srs");

  // Checks the output before the (long) work. The folder may exist and hold other files: only the
  // files gridify writes are replaced (with -overwrite), never the folder or anything else in it.
  io::OutputRules rules;
  rules.overwrite = args.flag("-overwrite");
  rules.isFolder = true;
  rules.entries = {kOutputFiles.begin(), kOutputFiles.end()};
  rules.inputs = ctx.inputs;
  io::RasterWriteOptions raster;
  raster.creationOptions = {"COMPRESS=DEFLATE"};
  // vectorize reads it: roads rasterized from mapped streets are real roads (-road-removals auto).
  raster.metadata[app::kRoadSourceKey] = app::kMappedStreets;
  for (const std::string& co : args.values("-co")) raster.creationOptions.push_back(co);
  io::checkRasterWriteOptions(raster);
  io::AtomicOutput output(outputDir, rules);

  const Progress readProgress = subProgress(ctx.progress, 0.0, 0.3);
  reportProgress(readProgress, 0.0, "reading");
  gridify::CityData city = app::readCitySource(input, source, ctx.warn);
  if (!landCover.raster.empty()) {
    reportProgress(readProgress, 0.9, "land cover");
    city.landCover = app::readLandCover(landCover, gridify::gridFrame(city, options));
  }
  reportProgress(readProgress, 1.0, "reading");
  gridify::GridifyResult result = gridify::gridify(city, options, subProgress(ctx.progress, 0.3, 0.9));

  const std::string crsName = io::crsShortName(result.spec.crsWkt);
  for (Layer& layer : result.truth)
    if (layer.name == "grid_info") layer.features[0].values[4] = crsName;

  namespace fs = std::filesystem;
  const fs::path dir(output.tempPath());
  io::writeRasterBand((dir / "landuse.tif").string(), result.spec, result.landUse, kLandUseNodata, raster);
  io::writeRasterBand((dir / "density.tif").string(), result.spec, result.density, std::nullopt, raster);
  io::writeRasterBand((dir / "parcels.tif").string(), result.spec, result.parcelIds, std::nullopt, raster);
  writeParcelsCsv((dir / "parcels.csv").string(), result.parcels);
  io::VectorWriteOptions vector;
  vector.crsWkt = result.spec.crsWkt;
  io::writeVectorDataset((dir / "truth.gpkg").string(), result.truth, vector);
  reportProgress(ctx.progress, 0.99, "writing");
  output.commit(ctx.progress);
  reportProgress(ctx.progress, 1.0, "done");

  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!ctx.quiet && ctx.out) {
    double population = 0.0;
    for (const auto& p : result.parcels) population += p.population;
    *ctx.out << "gridify: " << result.spec.width << " x " << result.spec.height << " cells of "
             << options.cellSize << " m in " << crsName << "; " << result.roadsRasterized << " roads, "
             << result.parcels.size() << " parcels, population " << static_cast<long long>(population + 0.5)
             << "; " << seconds << " s\n";
    if (!landCover.raster.empty())
      *ctx.out << "land cover: " << result.landCoverCells
               << " cells no land-use polygon covers took their class from '" << landCover.raster << "'\n";
    if (options.untagged.enabled)
      *ctx.out << "untagged land: " << result.inferredCells << " cells in "
               << result.untaggedByBuildings + result.untaggedByStreets + result.untaggedByDefault
               << " blocks took a use (" << result.untaggedByBuildings << " by their buildings, "
               << result.untaggedByStreets << " by their streets, " << result.untaggedByDefault
               << " by -default-use)\n";
  }
}

const bool registered = app::registerCommand(spec(), run);

}  // namespace
}  // namespace urbanvec
