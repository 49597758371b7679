// `urbanvec vectorize`: gridded land use -> vector road network (issue 3: spec sexton-vectorizer.md
// stages A1–A5, B1–B6; docs/vectorize.md).
#include <sys/stat.h>

#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <sstream>

#include "urbanvec/app/command.hpp"
#include "urbanvec/app/grid_input.hpp"
#include "urbanvec/core/error.hpp"
#include "urbanvec/core/memory.hpp"
#include "urbanvec/core/parallel.hpp"
#include "urbanvec/io/atomic_output.hpp"
#include "urbanvec/io/vector_io.hpp"
#include "urbanvec/vectorize/pipeline.hpp"
#include "urbanvec/vectorize/roads/road_checks.hpp"
#include "urbanvec/vectorize/roads/road_output.hpp"

namespace urbanvec {
namespace {

using app::option;
using app::Role;

/// Bytes of a file, or of every file under a folder (a per-layer output); 0 when missing.
std::uintmax_t bytesOnDisk(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (path.empty()) return 0;
  if (fs::is_regular_file(path, ec)) return fs::file_size(path, ec);
  std::uintmax_t sum = 0;
  if (fs::is_directory(path, ec))
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(path, ec))
      if (e.is_regular_file(ec)) sum += e.file_size(ec);
  return sum;
}

/// The -timings memory line: the run's peak resident memory, the stage it fell in, and its ratio to
/// the input files plus the output written (issue 21's target is at most 2).
void printMemoryLine(std::ostream& s, const std::vector<vectorize::StageReport>& stages,
                     const app::GridInputPaths& paths, const std::string& output) {
  const long peak = processPeakMemoryKb();
  if (peak < 0) {
    s << "memory: unknown on this system\n";
    return;
  }
  // The last stage's window (since its reset) runs on through the writing of the output.
  std::string where = "reading the input";
  long best = -1;
  for (const vectorize::StageReport& r : stages)
    if (r.peakMemoryKb > best) {
      best = r.peakMemoryKb;
      where = "stage " + r.id;
    }
  if (peakMemoryKb() > best) {
    best = peakMemoryKb();
    where = "writing the output";
  }
  if (peak > best) where = "reading the input";
  std::uintmax_t input = 0;
  for (const std::string* p : {&paths.landUse, &paths.density, &paths.parcels, &paths.parcelTable,
                               &paths.classes, &paths.openRegions})
    input += bytesOnDisk(*p);
  const std::uintmax_t written = bytesOnDisk(output);
  const double mb = 1024.0 * 1024.0;
  s << std::fixed << std::setprecision(1) << "memory: peak " << peak / 1024.0 << " MB (" << where
    << "), input " << input / mb << " MB, output " << written / mb
    << " MB, peak / (input + output) = " << std::setprecision(2)
    << (input + written > 0 ? peak * 1024.0 / static_cast<double>(input + written) : 0.0) << "\n";
}
using app::ValueType;

/// A default taken from the options struct, printed without trailing zeros.
app::CommandSpec spec() {
  const vectorize::VectorizeOptions d;
  app::CommandSpec s;
  s.name = "vectorize";
  s.summary = "Turns gridded urban land use into a vector city: roads, pavement, blocks, spines, parcels.";
  s.description =
      "Implements Sexton's vectorizer: simulated blocks by flood fill, extraneous intersection patch "
      "cleaning, a road graph on 1-wide secondary and 2-wide primary road cells, external block perimeters, "
      "intersection straightening, smoothing, primary/secondary connection, short-cycle removal, "
      "intersection simplification and curve smoothing; then curbs, pavement and culs-de-sac, blocks "
      "(internal, external, water split, matched to the simulated blocks), spines, parcels by spine and "
      "regular subdivision with land use and population (best of -tries per block, blocks in parallel). "
      "Writes the layers roads (one LineString per segment between intersections, dead ends or class "
      "changes; perimeters as road_class=perimeter), road_nodes, pavement, blocks, water, spines, parcels "
      "and the table vectorize_report, in the CRS of the land-use raster. All rasters given together must "
      "share size, geotransform and CRS. Distances are in cells (patch widths). See docs/vectorize.md.";
  s.group = "Vectorization";
  s.positionals = {
      {"landuse", "Land-use raster: class codes 0..8 (255 nodata), or any values mapped with -classes.",
       Role::InputRaster},
      {"output", "Output vector dataset (GeoPackage by default).", Role::OutputVector}};
  auto& o = s.options;
  o.push_back(option("-density", ValueType::String, "<raster>", "Population per cell (Float32), same grid.")
                  .withRole(Role::InputRaster));
  o.push_back(
      option("-parcels", ValueType::String, "<raster>", "Parcel id per cell (Int32, 0 = none), same grid.")
          .withRole(Role::InputRaster));
  o.push_back(option("-parcel-table", ValueType::String, "<csv>",
                     "Parcel list parcel_id,land_use,population,cells (needs -parcels).")
                  .withRole(Role::InputFile));
  o.push_back(
      option("-classes", ValueType::String, "<csv>",
             "Table value,class_name mapping the land-use raster's values to the nine classes (nodata = "
             "unused), for rasters from other simulations or land-cover products.")
          .withRole(Role::InputFile));
  o.push_back(option("-srcwin", ValueType::Integer, "<xoff> <yoff> <xsize> <ysize>",
                     "Vectorize only this window of the rasters, in cells (as gdal_translate -srcwin): only "
                     "the window is read, and the output is georeferenced at its place. Random draws are "
                     "keyed by whole-raster cells, so a block inside the window gets the parcels it gets in "
                     "a run on the whole grid (urbanvec-tiles, docs/scale.md).")
                  .values(4)
                  .isAdvanced());
  o.push_back(option("-open-regions", ValueType::String, "<raster>",
                     "Byte raster on the same grid: 1 where the cell's road-bounded region (4-connected "
                     "non-road cells) reaches the edge of the whole grid, 0 where roads enclose it. Stage A2 "
                     "then takes a region's open or enclosed status from it, not from the window's edge, so "
                     "a -srcwin window classes the regions it cuts as the whole grid does (urbanvec-tiles "
                     "writes it, docs/scale.md).")
                  .withRole(Role::InputRaster)
                  .isAdvanced());
  o.push_back(app::seedOption());
  o.push_back(option("-tries", ValueType::Integer, "<n>",
                     "Generate-and-test iterations per block; the lowest-cost parcelling is kept (E5).")
                  .byDefault(std::to_string(vectorize::parcels::ParcelsOptions{}.tries))
                  .atLeast(1));
  o.push_back(option("-patience", ValueType::Integer, "<n>",
                     "Stop a block's search once its best parcelling is complete and has not improved for n "
                     "tries in a row (0 = always run all -tries). Trades parcel cost for time; see "
                     "docs/performance.md.")
                  .byDefault(std::to_string(vectorize::parcels::ParcelsOptions{}.patience))
                  .atLeast(0)
                  .isAdvanced());
  o.push_back(
      option("-spine-method", ValueType::Choice, "<method>",
             "How block spines are found (D6): the thesis's Zhang-Suen thinning or CGAL's straight skeleton.")
          .oneOf({"zhang-suen", "skeleton"})
          .byDefault(
              std::string(vectorize::parcels::spineMethodName(vectorize::parcels::SpineOptions{}.method))));
  o.push_back(
      option("-threads", ValueType::Integer, "<n>",
             "Threads for the road and block stages (0 = all cores); the output does not depend on it.")
          .byDefault("0")
          .atLeast(0)
          .isAdvanced());
  o.push_back(option("-roads-only", ValueType::Flag, "",
                     "Stop after the road network (stages A-B): write only roads and road_nodes."));
  for (const app::OptionSpec& v : app::vectorOutputOptions()) o.push_back(v);
  o.push_back(
      option("-debug-stages", ValueType::String, "<dir>",
             "Write the road graph after each stage (links and nodes layers per stage) to <dir>/stages.gpkg.")
          .withRole(Role::OutputFolder)
          .isAdvanced());
  o.push_back(
      option("-timings", ValueType::Flag, "", "Print time, peak memory and counts per stage.").isAdvanced());
  o.push_back(
      option("-check", ValueType::Flag, "",
             "Check the road topology (crossings only at shared nodes, no zero-length pieces, no duplicate "
             "nodes) and that every road cell lies within 1.5 cells of an output road (except cells the "
             "pipeline removes on purpose), and print the result; a failed topology check is an error, a "
             "failed coverage check a warning.")
          .isAdvanced());
  o.push_back(
      option("-primary-node", ValueType::Choice, "<where>",
             "Primary node at the patch's south-east corner (paper) or the south-east neighbour's centre "
             "(thesis).")
          .oneOf({"corner", "neighbour"})
          .byDefault("corner")
          .isAdvanced());
  o.push_back(
      option("-max-link", ValueType::Real, "<cells>", "Links this long or longer are subdivided (A4.6).")
          .byDefault(app::numberText(d.roadGraph.maxLinkLength))
          .withUnit("cells")
          .atLeast(0.1)
          .isAdvanced());
  o.push_back(option("-straighten-window", ValueType::Real, "<cells>",
                     "Intersection straightening fits nodes within this distance (B1).")
                  .byDefault(app::numberText(d.straightening.window))
                  .withUnit("cells")
                  .atLeast(0)
                  .isAdvanced());
  o.push_back(option("-straighten-residual", ValueType::Real, "<cells>",
                     "Largest residual norm of a fit that is snapped (B1).")
                  .byDefault(app::numberText(d.straightening.maxResidual))
                  .withUnit("cells")
                  .atLeast(0)
                  .isAdvanced());
  o.push_back(option("-smooth-passes", ValueType::Integer, "<n>", "Road smoothing passes (B2).")
                  .byDefault(app::numberText(d.roadSmoothing.passes))
                  .atLeast(0)
                  .isAdvanced());
  o.push_back(
      option("-perimeter-passes", ValueType::Integer, "<n>", "Smoothing passes of perimeter lines (B2, Q8).")
          .byDefault(app::numberText(d.roadSmoothing.perimeterPasses))
          .atLeast(0)
          .isAdvanced());
  o.push_back(option("-smooth-reach", ValueType::Real, "<cells>",
                     "Smoothing (B2, B6) keeps every node within this distance of the road cells it was "
                     "placed for (0 = no limit).")
                  .byDefault(app::numberText(d.roadSmoothing.reach))
                  .withUnit("cells")
                  .atLeast(0)
                  .isAdvanced());
  o.push_back(option("-no-through-roads", ValueType::Flag, "",
                     "Skip B7: intersections at the crossing of their through roads, straight roads drawn "
                     "straight (docs/vectorize.md, \"Through roads and straight roads\").")
                  .isAdvanced());
  o.push_back(option("-through-angle", ValueType::Real, "<degrees>",
                     "Two arms of an intersection continue each other when within this of opposite (B7).")
                  .byDefault(app::numberText(d.throughRoads.pairAngle))
                  .withUnit("degrees")
                  .atLeast(0)
                  .atMost(90)
                  .isAdvanced());
  o.push_back(option("-through-fit-reach", ValueType::Real, "<cells>",
                     "An intersection's straight arms are fitted on their road up to this far from it, while "
                     "the road stays straight (B7; " +
                         app::numberText(d.throughRoads.window) +
                         ", the approach window, or less = fitted within the window).")
                  .byDefault(app::numberText(d.throughRoads.fitReach))
                  .withUnit("cells")
                  .atLeast(0)
                  .isAdvanced());
  o.push_back(option("-junction-span", ValueType::Real, "<factor>",
                     "Junctions joined by a road no longer than this many times the summed widths of that "
                     "road and the widest other road at its ends form a cluster, rebuilt as the junctions "
                     "its through roads' lines imply (B7; 0 = off).")
                  .byDefault(app::numberText(d.throughRoads.junctionSpan))
                  .atLeast(0)
                  .isAdvanced());
  o.push_back(option("-straight-slack", ValueType::Real, "<cells>",
                     "A road is straight when its cells lie within the band of a digital straight line "
                     "plus this (B7).")
                  .byDefault(app::numberText(d.throughRoads.slack))
                  .withUnit("cells")
                  .atLeast(0)
                  .isAdvanced());
  o.push_back(option("-straight-angle", ValueType::Real, "<degrees>",
                     "Road pairs straighter than this re-straighten their intersection (B2).")
                  .byDefault(app::numberText(d.roadSmoothing.straightAngle))
                  .withUnit("degrees")
                  .atLeast(90)
                  .atMost(180)
                  .isAdvanced());
  o.push_back(option("-no-patch-cleaning", ValueType::Flag, "",
                     "Skip the extraneous intersection patch cleaning (A3): keep the secondary strips "
                     "beside primary roads.")
                  .isAdvanced());
  o.push_back(
      option("-road-removals", ValueType::Choice, "<mode>",
             "The roads the documents remove on purpose (A3 secondary strips beside a primary, B4 short "
             "cycles, B5 dead ends near another road): paper removes them; none keeps every road the grid "
             "shows (B4 then removes only loops around no land cell); auto is none on grids gridify "
             "rasterized from mapped streets (metadata URBANVEC_ROAD_SOURCE=mapped_streets) and paper "
             "otherwise. With auto, -no-patch-cleaning, -cycle-nodes or -dead-end-angle select paper.")
          .oneOf({"auto", "paper", "none"})
          .byDefault("auto"));
  o.push_back(option("-keep-all-roads", ValueType::Flag, "",
                     "Alias of -road-removals none. Not with -cycle-nodes or -dead-end-angle.")
                  .isAdvanced());
  o.push_back(option("-cycle-nodes", ValueType::Integer, "<n>",
                     "Road cycles of at most this many nodes lose a segment (B4).")
                  .byDefault(app::numberText(d.cycles.maxCycleNodes))
                  .atLeast(0)
                  .isAdvanced());
  o.push_back(option("-dead-end-angle", ValueType::Real, "<degrees>",
                     "Dead ends at an intersection closer than this angle to another road are removed (B5).")
                  .byDefault(app::numberText(d.intersections.deadEndAngle))
                  .withUnit("degrees")
                  .atLeast(0)
                  .atMost(180)
                  .isAdvanced());
  o.push_back(option("-primary-close", ValueType::Real, "<cells>",
                     "Primary nodes closer than this to an intersection are merged into it (B5).")
                  .byDefault(app::numberText(d.intersections.primaryDistance))
                  .withUnit("cells")
                  .atLeast(0)
                  .isAdvanced());
  o.push_back(option("-secondary-close", ValueType::Real, "<cells>",
                     "Secondary nodes closer than this to an intersection are merged into it (B5).")
                  .byDefault(app::numberText(d.intersections.secondaryDistance))
                  .withUnit("cells")
                  .atLeast(0)
                  .isAdvanced());
  o.push_back(option("-curve-passes", ValueType::Integer, "<n>", "Curve smoothing passes (B6).")
                  .byDefault(app::numberText(d.curves.passes))
                  .atLeast(0)
                  .isAdvanced());
  o.push_back(option("-curve-angles", ValueType::Real, "<a3> <a2> <a1>",
                     "Bends sharper than these interior angles get 3, 2, 1 extra nodes per side (B6).")
                  .values(3)
                  .byDefault(app::numberText(d.curves.angleThreeNodes) + " " +
                             app::numberText(d.curves.angleTwoNodes) + " " +
                             app::numberText(d.curves.angleOneNode))
                  .withUnit("degrees")
                  .atLeast(0)
                  .atMost(180)
                  .isAdvanced());
  o.push_back(
      option("-simplify", ValueType::Real, "<cells>",
             "Tolerance of the topology-preserving simplification of the output segments (0 = keep every "
             "graph node).")
          .byDefault(app::numberText(d.outputSimplification))
          .withUnit("cells")
          .atLeast(0)
          .isAdvanced());
  o.push_back(option("-curve-tolerance", ValueType::Real, "<cells>",
                     "Curved pieces of the output segments (both ends turning the same way) are drawn on the "
                     "spline through the segment's vertices, within this distance of it (0 = straight pieces "
                     "between the simplified vertices).")
                  .byDefault(app::numberText(d.curveDrawing.tolerance))
                  .withUnit("cells")
                  .atLeast(0)
                  .isAdvanced());
  s.examples = {
      "urbanvec vectorize -density density.tif -parcels parcels.tif -parcel-table parcels.csv landuse.tif "
      "city.gpkg",
      "urbanvec vectorize -classes corine_classes.csv -debug-stages stages landcover.tif roads.gpkg"};
  s.outputLayers = {"roads", "road_nodes", "pavement", "blocks",
                    "water", "spines",     "parcels",  "vectorize_report"};
  return s;
}

void run(const app::ParsedArgs& args, app::CommandContext& ctx) {
  const std::string landUse = args.positionals()[0];
  const std::string output = args.positionals()[1];
  const bool overwrite = args.flag("-overwrite");

  vectorize::VectorizeOptions options;
  options.roadGraph.primaryNodeAtCorner = args.str("-primary-node") == "corner";
  options.roadGraph.maxLinkLength = args.real("-max-link");
  options.connection.maxLinkLength = options.roadGraph.maxLinkLength;
  options.straightening.window = args.real("-straighten-window");
  options.straightening.maxResidual = args.real("-straighten-residual");
  options.roadSmoothing.passes = static_cast<int>(args.integer("-smooth-passes"));
  options.roadSmoothing.perimeterPasses = static_cast<int>(args.integer("-perimeter-passes"));
  options.roadSmoothing.straightAngle = args.real("-straight-angle");
  options.roadSmoothing.reach = args.real("-smooth-reach");
  options.curves.reach = options.roadSmoothing.reach;
  options.throughRoads.reach = options.roadSmoothing.reach;
  options.throughRoads.enabled = !args.flag("-no-through-roads");
  options.throughRoads.pairAngle = args.real("-through-angle");
  options.throughRoads.slack = args.real("-straight-slack");
  options.throughRoads.fitReach = args.real("-through-fit-reach");
  options.throughRoads.junctionSpan = args.real("-junction-span");
  options.cycles.maxCycleNodes = static_cast<int>(args.integer("-cycle-nodes"));
  options.intersections.deadEndAngle = args.real("-dead-end-angle");
  options.cleanIntersectionPatches = !args.flag("-no-patch-cleaning");
  std::string removalsChosenBy;  // the option that chose the road removals; empty: the grid's metadata
  {
    const std::string mode = args.str("-road-removals");
    const bool alias = args.flag("-keep-all-roads");
    if (alias && args.given("-road-removals") && mode != "none")
      throw invalidOption("-keep-all-roads is -road-removals none; do not give -road-removals " + mode +
                          " with it");
    const bool tuned =
        args.given("-cycle-nodes") || args.given("-dead-end-angle") || args.flag("-no-patch-cleaning");
    if (alias || mode == "none") {
      for (const char* removal : {"-cycle-nodes", "-dead-end-angle"})
        if (args.given(removal))
          throw invalidOption(std::string(alias ? "-keep-all-roads" : "-road-removals none") +
                              " switches the road removals off; do not give " + removal + " with it");
      options.roadRemovals = vectorize::RoadRemovals::None;
      removalsChosenBy = alias ? "-keep-all-roads" : "-road-removals none";
    } else if (mode == "paper" || tuned) {
      options.roadRemovals = vectorize::RoadRemovals::Paper;
      removalsChosenBy = mode == "paper"                 ? std::string("-road-removals paper")
                         : args.given("-cycle-nodes")    ? std::string("-cycle-nodes given")
                         : args.given("-dead-end-angle") ? std::string("-dead-end-angle given")
                                                         : std::string("-no-patch-cleaning given");
    } else {
      options.roadRemovals = vectorize::RoadRemovals::Auto;
    }
  }
  options.intersections.primaryDistance = args.real("-primary-close");
  options.intersections.secondaryDistance = args.real("-secondary-close");
  options.curves.passes = static_cast<int>(args.integer("-curve-passes"));
  {
    const std::vector<std::string> a = args.values("-curve-angles");
    if (a.size() == 3) {
      options.curves.angleThreeNodes = std::stod(a[0]);
      options.curves.angleTwoNodes = std::stod(a[1]);
      options.curves.angleOneNode = std::stod(a[2]);
      if (!(options.curves.angleThreeNodes <= options.curves.angleTwoNodes &&
            options.curves.angleTwoNodes <= options.curves.angleOneNode))
        throw invalidOption("-curve-angles must be increasing (for 3, 2, 1 nodes), got " + a[0] + " " + a[1] +
                            " " + a[2]);
    }
  }
  options.outputSimplification = args.real("-simplify");
  options.curveDrawing.tolerance = args.real("-curve-tolerance");
  options.roadsOnly = args.flag("-roads-only");
  options.city.parcels.seed = static_cast<std::uint64_t>(args.integer("-seed"));
  options.city.parcels.tries = static_cast<int>(args.integer("-tries"));
  options.city.parcels.patience = static_cast<int>(args.integer("-patience"));
  options.city.parcels.threads = static_cast<int>(args.integer("-threads"));
  options.city.parcels.spine.method = *vectorize::parcels::parseSpineMethod(args.str("-spine-method"));
  const bool debug = args.given("-debug-stages");
  options.keepStageGraphs = debug;

  // Check the outputs up front, before any work: format, creation options, name, inputs.
  io::VectorWriteOptions write;
  if (args.has("-of")) write.format = args.str("-of");
  write.layerCreationOptions = args.values("-lco");
  write.datasetCreationOptions = args.values("-dsco");
  io::OutputRules rules;
  rules.overwrite = overwrite;
  rules.inputs = ctx.inputs;
  io::VectorOutput out(
      output, write,
      options.roadsOnly ? std::vector<std::string>{"roads", "road_nodes"} : spec().outputLayers, rules);
  // A -debug-stages folder this run creates goes again when the run fails (declared before debugOut,
  // so the temporary file inside is gone first).
  struct CreatedFolders {
    std::vector<std::filesystem::path> made;  ///< folders this run itself created, outermost first
    bool keep = false;
    ~CreatedFolders() {
      std::error_code ec;
      for (auto it = made.rbegin(); !keep && it != made.rend(); ++it) std::filesystem::remove(*it, ec);
    }
  } createdFolders;
  std::unique_ptr<io::AtomicOutput> debugOut;
  if (debug) {
    namespace fs = std::filesystem;
    const std::string dir = args.str("-debug-stages");
    std::error_code ec;
    // Each level is made with one mkdir, and only the ones this run made are removed on failure (and
    // only when empty): another run creating the same folders at once keeps its own.
    std::vector<fs::path> levels;
    for (fs::path p = fs::absolute(dir, ec); !p.empty() && !ec && !fs::exists(p, ec); p = p.parent_path()) {
      levels.push_back(p);
      if (p == p.parent_path()) break;
    }
    for (auto it = levels.rbegin(); it != levels.rend(); ++it)
      if (::mkdir(it->c_str(), 0777) == 0) createdFolders.made.push_back(*it);
    if (!fs::is_directory(dir, ec)) throw invalidOption("-debug-stages: cannot create folder '" + dir + "'");
    const fs::path stages = fs::path(dir) / "stages.gpkg";
    if (fs::weakly_canonical(fs::absolute(stages), ec) == fs::weakly_canonical(fs::absolute(output), ec))
      throw invalidOption("-debug-stages '" + dir + "' would write stages.gpkg, which is the output '" +
                          output + "'; choose another folder or output name");
    debugOut = std::make_unique<io::AtomicOutput>(stages.string(), rules);
  }

  app::GridInputPaths paths;
  paths.landUse = landUse;
  if (args.given("-density")) paths.density = args.str("-density");
  if (args.given("-parcels")) paths.parcels = args.str("-parcels");
  if (args.given("-parcel-table")) paths.parcelTable = args.str("-parcel-table");
  if (args.given("-classes")) paths.classes = args.str("-classes");
  if (args.given("-open-regions")) paths.openRegions = args.str("-open-regions");
  if (args.given("-srcwin")) {
    const std::vector<std::string> w = args.values("-srcwin");
    int v[4];
    for (int k = 0; k < 4; ++k) {
      const long long x = std::stoll(w[static_cast<size_t>(k)]);
      if (x < -2147483647LL || x > 2147483647LL)
        throw invalidOption("-srcwin value " + w[static_cast<size_t>(k)] + " is out of range");
      v[k] = static_cast<int>(x);
    }
    paths.window = io::RasterWindow{v[0], v[1], v[2], v[3]};
  }
  std::vector<std::string> warnings;
  vectorize::VectorizeInput input = app::loadGridInput(paths, &warnings);
  for (const std::string& w : warnings) ctx.warn(w);
  // Auto decides from metadata that some GDAL tools keep and others drop (docs/vectorize.md, "Choosing
  // the removals from the grid"), so the user sees which mode ran and why.
  if (!ctx.quiet && ctx.out) {
    const bool keepAll = vectorize::keepsAllRoads(options.roadRemovals, input);
    *ctx.out << "road removals: " << (keepAll ? "none" : "paper") << " ("
             << (!removalsChosenBy.empty() ? removalsChosenBy
                                           : landUse + (input.roadsFromMappedStreets ? " has " : " has no ") +
                                                 app::kRoadSourceKey + "=" + app::kMappedStreets)
             << ")\n";
  }

  // Each layer is written as soon as the pipeline has made it final: with more than one worker on a
  // thread of its own while the later stages compute (roads and road_nodes during C-E, pavement
  // during the parcel search), with one worker at once, in this thread. The same file either way.
  const bool runCheck = args.flag("-check");
  std::vector<Layer> roadLayers;  // copies of roads and road_nodes for -check
  io::LayerStream stream(out, input.spec.crsWkt, workerCount(options.city.parcels.threads) > 1);
  const LayerSink sink = [&](Layer&& layer) {
    if (runCheck && roadLayers.size() < 2) roadLayers.push_back(layer);
    stream.add(std::move(layer));
  };
  // The density and parcel grids go once A5 has read them.
  vectorize::VectorizeResult result = vectorize::vectorizeReleasingInput(input, options, ctx.progress, sink);
  for (const std::string& w : result.warnings) ctx.warn(w);

  if (runCheck) {
    const vectorize::RoadNetworkCheck check = vectorize::checkRoadNetwork(roadLayers.at(0), roadLayers.at(1));
    const vectorize::RoadCoverageCheck coverage = vectorize::checkRoadCoverage(
        input.landUse, result.cells, result.network, result.cycleRemovedLinks, result.deadEndRemovedLinks);
    if (ctx.out) *ctx.out << "topology: " << check.describe() << "\n" << coverage.describe() << "\n";
    if (!check.ok()) throw internalError("the road topology check failed: " + check.describe());
    // Coverage is a quality figure, not part of the output contract: a shortfall is reported, and the
    // output is still written.
    if (!coverage.ok())
      ctx.warn("the road coverage check failed: " + std::to_string(coverage.far) +
               " road cells are farther than " + app::numberText(coverage.maxDistance) +
               " cells from every output road");
  }

  // Only the stage reports and the -debug-stages graphs are needed from here: the rest of the result
  // (grids, simulated blocks, network, reports per block) goes before the last layers are written.
  std::vector<vectorize::StageReport> stages = std::move(result.stages);
  std::vector<std::pair<std::string, vectorize::RoadGraph>> stageGraphs = std::move(result.stageGraphs);
  result = vectorize::VectorizeResult();
  std::vector<Layer>().swap(roadLayers);
  input.landUse = Grid<std::uint8_t>();
  input.openRegions = Grid<std::uint8_t>();
  releaseFreedMemory();
  stream.finish();
  if (debugOut) {
    std::vector<Layer> layers;
    int k = 0;
    for (const auto& [stage, graph] : stageGraphs) {
      std::ostringstream prefix;
      prefix << std::setw(2) << std::setfill('0') << ++k << "_" << stage << "_";
      std::string p = prefix.str();
      for (char& c : p)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
      for (Layer& l : vectorize::rawGraphLayers(graph, input.spec, p)) layers.push_back(std::move(l));
    }
    io::VectorWriteOptions dw;
    dw.format = "GPKG";
    dw.crsWkt = input.spec.crsWkt;
    io::writeVectorDataset(debugOut->tempPath(), layers, dw);
    debugOut->commit(ctx.progress);
  }
  out.commit(ctx.progress);
  createdFolders.keep = true;

  if (args.flag("-timings") && ctx.out) {
    std::ostream& s = *ctx.out;
    s << "stage  name                          seconds  peak_MB    nodes    links  summary\n";
    for (const vectorize::StageReport& r : stages)
      s << std::left << std::setw(6) << r.id << " " << std::setw(29) << r.name << std::right << std::fixed
        << std::setprecision(3) << std::setw(8) << r.seconds << " " << std::setw(8) << std::setprecision(1)
        << (r.peakMemoryKb >= 0 ? r.peakMemoryKb / 1024.0 : -1.0) << " " << std::setw(8) << r.nodes << " "
        << std::setw(8) << r.links << "  " << r.summary << "\n";
    printMemoryLine(s, stages, paths, output);
  }
}

const bool registered = app::registerCommand(spec(), run);

}  // namespace
}  // namespace urbanvec
