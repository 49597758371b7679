// The pipeline of spec §1 top-down: A1–A5 and B1–B6 here, each timed and measured, then C–E (city_pipeline).
#include "urbanvec/vectorize/pipeline.hpp"

#include <algorithm>
#include <chrono>
#include <functional>
#include <limits>
#include <optional>
#include <sstream>

#include "urbanvec/core/error.hpp"
#include "urbanvec/core/memory.hpp"
#include "urbanvec/vectorize/roads/road_checks.hpp"
#include "urbanvec/vectorize/roads/road_output.hpp"

namespace urbanvec::vectorize {

namespace {

void validate(const VectorizeInput& in) {
  const Grid<std::uint8_t>& lu = in.landUse;
  if (lu.width <= 0 || lu.height <= 0 || lu.cells.size() != static_cast<size_t>(lu.width) * lu.height)
    throw invalidInput("the land-use grid has no cells");
  if (in.spec.width != lu.width || in.spec.height != lu.height)
    throw invalidInput("the land-use grid is " + std::to_string(lu.width) + "x" + std::to_string(lu.height) +
                       " cells but its grid description says " + std::to_string(in.spec.width) + "x" +
                       std::to_string(in.spec.height));
  for (size_t i = 0; i < lu.cells.size(); ++i)
    if (lu.cells[i] >= kLandUseClassCount)
      throw invalidInput("the land-use grid holds value " + std::to_string(lu.cells[i]) + " at column " +
                         std::to_string(i % lu.width) + ", row " + std::to_string(i / lu.width) +
                         ", which is not a class code 0..8");
  if (in.density.size() != 0 && (in.density.width != lu.width || in.density.height != lu.height))
    throw invalidInput("the density grid does not have the size of the land-use grid");
  if (in.parcelIds.size() != 0) {
    if (in.parcelIds.width != lu.width || in.parcelIds.height != lu.height)
      throw invalidInput("the parcel grid does not have the size of the land-use grid");
    for (size_t i = 0; i < in.parcelIds.cells.size(); ++i)
      if (in.parcelIds.cells[i] < 0)
        throw invalidInput("the parcel grid holds negative parcel id " +
                           std::to_string(in.parcelIds.cells[i]) + " at column " +
                           std::to_string(i % lu.width) + ", row " + std::to_string(i / lu.width) +
                           " (ids must be >= 0, 0 = no parcel)");
  }
}

template <class... T>
std::string counts(const T&... parts) {
  std::ostringstream s;
  ((s << parts), ...);
  return s.str();
}

/// The input's population figures the final warnings need, taken before A5 so that the density and
/// parcel grids can go once A5 has read them (vectorizeReleasingInput).
struct InputPopulation {
  bool hasParcels = false;
  bool hasParcelTable = false;
  double density = 0;
  double densityWithoutParcel = 0;
  std::size_t cellsWithoutParcel = 0;
};

InputPopulation inputPopulation(const VectorizeInput& input) {
  InputPopulation s;
  s.hasParcels = input.parcelIds.size() != 0;
  s.hasParcelTable = !input.parcelTable.empty();
  for (size_t i = 0; i < input.density.cells.size(); ++i) {
    s.density += input.density.cells[i];
    if (s.hasParcels && input.parcelIds.cells[i] == 0 && input.density.cells[i] > 0) {
      s.densityWithoutParcel += input.density.cells[i];
      ++s.cellsWithoutParcel;
    }
  }
  return s;
}

/// Every person of the input reaches a parcel of the parcels layer, or the warnings say where the
/// others went (the A5 warning already names the parcels outside every block).
void populationWarnings(const InputPopulation& input, VectorizeResult& result) {
  if (!input.hasParcels && input.density > 0)
    result.warnings.push_back("the density grid holds " + peopleText(input.density) +
                              ", but without a parcels grid (-parcels) there are no input parcels to "
                              "carry them: " +
                              (result.city.blocks.blockInfo.empty()
                                   ? "the parcels layer is empty (the grid has no blocks)"
                                   : "each block is one undeveloped parcel with population 0"));
  // With a parcel table the table's population replaces the density grid's.
  if (!input.hasParcelTable && input.cellsWithoutParcel > 0)
    result.warnings.push_back(peopleText(input.densityWithoutParcel) + " of the density grid lie on " +
                              std::to_string(input.cellsWithoutParcel) +
                              (input.cellsWithoutParcel == 1 ? " cell" : " cells") +
                              " without a parcel (id 0) and reach no parcel of the parcels layer");
  double inBlocks = 0, unmatched = 0;
  const std::vector<int>& vectorBlockOfSim = result.city.blocks.matching.vectorBlockOfSim;
  for (const SimParcel& p : result.parcels) {
    if (p.simBlock < 0) continue;
    inBlocks += p.population;
    if (static_cast<size_t>(p.simBlock) >= vectorBlockOfSim.size() || vectorBlockOfSim[p.simBlock] < 0)
      unmatched += p.population;
  }
  double kept = 0, ignored = 0;
  for (const parcels::BlockParcels& b : result.city.parcels.blocks) {
    ignored += b.report.ignoredPopulation;
    for (const parcels::VectorParcel& parcel : b.parcels) kept += parcel.population;
  }
  const double lost = inBlocks - kept;
  if (!(lost > 1e-6 * std::max(1.0, inBlocks))) return;
  std::string why;
  if (unmatched > 0) why += peopleText(unmatched) + " in simulated blocks that no vector block takes";
  if (ignored > 0)
    why += (why.empty() ? "" : ", ") + peopleText(ignored) +
           " of land uses that no parcel of their block gets (vectorize_report ignored_population)";
  const double unexplained = lost - unmatched - ignored;
  if (unexplained > 1e-6 * std::max(1.0, inBlocks))
    why += (why.empty() ? "" : ", and ") + peopleText(unexplained) + " lost for no reason the stages record";
  // peopleText(x) ends in " people" (or " person"): "12 of the 15 people".
  std::string keptNumber = peopleText(kept);
  keptNumber.resize(keptNumber.rfind(' '));
  result.warnings.push_back("the parcels layer holds " + keptNumber + " of the " + peopleText(inBlocks) +
                            " of the input parcels inside blocks" +
                            (why.empty() ? std::string() : "; the others are " + why));
}

}  // namespace

bool keepsAllRoads(RoadRemovals removals, const VectorizeInput& input) {
  return removals == RoadRemovals::None || (removals == RoadRemovals::Auto && input.roadsFromMappedStreets);
}

namespace {

/// The pipeline; `release`, when given, is `input` itself, whose density and parcel grids and parcel
/// table go once A5 has read them. `sink`: see vectorizeReleasingInput.
VectorizeResult runPipeline(const VectorizeInput& input, VectorizeInput* release,
                            const VectorizeOptions& options, const Progress& progress,
                            const LayerSink& sink) {
  validate(input);
  const InputPopulation population = inputPopulation(input);
  VectorizeResult result;
  result.cells = input.landUse;
  RoadGraph& graph = result.roads;
  result.roadsKept = keepsAllRoads(options.roadRemovals, input);

  // Stage runner: progress sub-range, timing, per-stage peak memory, graph snapshot. The road stages
  // take the first 30% of the progress range when stages C-E follow.
  const Progress roadProgress = options.roadsOnly ? progress : subProgress(progress, 0.0, 0.3);
  double done = 0;
  // Set by a stage that releases the graph before it ends (F): the counts it had when released.
  std::optional<std::pair<std::size_t, std::size_t>> releasedGraphCounts;
  auto run = [&](const std::string& id, const std::string& name, double weight, bool graphStage,
                 const std::function<std::string(const Progress&)>& body) {
    const Progress sub = subProgress(roadProgress, done, std::min(1.0, done + weight));
    reportProgress(sub, 0.0, name);
    resetPeakMemory();
    const auto t0 = std::chrono::steady_clock::now();
    StageReport report;
    report.id = id;
    report.name = name;
    report.summary = body(sub);
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    report.peakMemoryKb = peakMemoryKb();
    report.nodes = releasedGraphCounts ? releasedGraphCounts->first : graph.aliveCount();
    report.links = releasedGraphCounts ? releasedGraphCounts->second : graph.linkCount();
    result.stages.push_back(report);
    if (graphStage && options.keepStageGraphs) result.stageGraphs.emplace_back(id + " " + name, graph);
    done = std::min(1.0, done + weight);
    reportProgress(sub, 1.0, name);
  };

  // Each output layer, as soon as it is final: to the sink, or kept in the result.
  const LayerSink emit = sinkOrAppend(sink, result.layers);

  std::size_t roadCells = 0;
  for (std::uint8_t c : input.landUse.cells) roadCells += isRoadCode(c);
  if (roadCells == 0)
    result.warnings.push_back(
        "the land-use grid has no road cells (codes 2 and 3): the road layers are empty");
  else if (roadCells == input.landUse.cells.size())
    result.warnings.push_back(
        "every cell of the land-use grid is road: there are no blocks, and the road network collapses to "
        "intersection clusters");

  run("A2", "raw blocks", 0.05, false, [&](const Progress& p) {
    RawBlockOptions raw = options.rawBlocks;
    if (input.openRegions.size() != 0) raw.openRegions = &input.openRegions;
    RawBlocks rb = buildRawBlocks(result.cells, raw, p);
    result.blocks = std::move(rb.blocks);
    result.blockOf = std::move(rb.blockOf);
    std::size_t internal = 0;
    for (const SimBlock& b : result.blocks) internal += b.internal;
    return counts(result.blocks.size(), " blocks (", internal, " internal)");
  });
  run("A3", "patch cleaning", 0.05, false, [&](const Progress& p) {
    if (result.roadsKept) return std::string("skipped (road removals: none, every secondary patch kept)");
    if (!options.cleanIntersectionPatches) return std::string("skipped (every secondary patch kept)");
    const PatchCleaningStats s = cleanIntersectionPatches(result.cells, p, options.patchCleaning);
    return counts(s.searches, " clusters searched, ", s.removedPatches, " patches removed");
  });
  run("A4", "road graph", 0.2, true, [&](const Progress& p) {
    RoadGraphBuild b = buildRoadGraph(result.cells, options.roadGraph, p);
    graph = std::move(b.graph);
    return counts(b.squaresOpened, " 2x2 squares opened, ", b.squaresLeft, " left, ", b.clustersMerged,
                  " clusters merged, ", b.nodesInserted, " nodes inserted");
  });
  run("A4.8", "perimeters", 0.05, true, [&](const Progress& p) {
    const PerimeterStats s =
        addExternalPerimeters(graph, result.cells, result.blockOf, result.blocks, options.perimeters, p);
    if (s.closedLoops > 0)
      result.warnings.push_back(
          counts(s.closedLoops,
                 s.closedLoops == 1 ? " closed boundary between undeveloped land and external blocks meets"
                                    : " closed boundaries between undeveloped land and external blocks meet",
                 " no road and got no perimeter line (islands become blocks of their own outline)"));
    return counts(s.lines, " perimeter lines, ", s.closedLoops, " closed loops skipped");
  });
  run("A5", "parcels", 0.03, false, [&](const Progress& p) {
    ParcelLoading pl = loadParcels(input, result.blockOf, result.blocks, p, options.parcelLoading);
    result.parcels = std::move(pl.parcels);
    if (pl.unattached > 0)
      result.warnings.push_back(unattachedParcelsWarning(pl, options.parcelLoading.majorityBlock));
    // Nothing after A5 reads the block index per cell (4 bytes a cell), nor, when the caller lets
    // them go, the density and parcel grids (4 bytes a cell each) and the parcel table.
    result.blockOf = Grid<std::int32_t>();
    if (release) {
      release->density = Grid<float>();
      release->parcelIds = Grid<std::int32_t>();
      std::vector<ParcelRecord>().swap(release->parcelTable);
    }
    return counts(result.parcels.size(), " parcels, ", pl.unattached, " unattached, ", pl.derivedFromRaster,
                  " derived from the rasters");
  });
  run("B1", "intersection straightening", 0.1, true, [&](const Progress& p) {
    const StraighteningStats s = straightenIntersections(graph, options.straightening, p);
    return counts(s.intersections, " intersections, ", s.pairsSnapped, " pairs snapped");
  });
  run("B2", "road smoothing", 0.05, true, [&](const Progress& p) {
    RoadSmoothingOptions smoothing = options.roadSmoothing;
    smoothing.threads = options.city.parcels.threads;  // one thread setting for every parallel stage
    if (options.keepRoadCellsCovered) smoothing.coverCells = &result.cells;
    const RoadSmoothingStats s = smoothRoads(graph, smoothing, p);
    return counts(s.nodesMoved, " nodes smoothed, ", s.intersectionsMoved, " intersections re-straightened");
  });
  run("B3", "primary/secondary connection", 0.1, true, [&](const Progress& p) {
    const RoadConnectionStats s = connectRoads(graph, options.connection, p);
    return counts(s.connections, " connections, ", s.unconnected, " without a primary node in reach, ",
                  s.clustersMerged, " clusters merged, ", s.perimeterEndsLinked, " perimeter ends linked, ",
                  s.perimeterEndsLeft, " left");
  });
  run("B4", "cycle removal", 0.15, true, [&](const Progress& p) {
    CycleRemovalOptions cycles = options.cycles;
    cycles.threads = options.city.parcels.threads;
    if (options.keepDevelopedCycles || result.roadsKept) cycles.landUse = &result.cells;
    cycles.keepLandCycles = result.roadsKept;
    CycleRemovalStats s = removeShortCycles(graph, cycles, p);
    result.cycleRemovedLinks = std::move(s.removedLinks);
    return counts(s.crossingsNoded, " crossings noded, ", s.segmentsRemoved, " segments removed in ",
                  s.rounds, " rounds, ", s.developedFacesKept,
                  result.roadsKept ? " faces around land kept" : " faces around developed land kept");
  });
  run("B5", "intersection simplification", 0.05, true, [&](const Progress& p) {
    IntersectionSimplificationOptions simplification = options.intersections;
    if (options.keepRoadCellsCovered) simplification.coverCells = &result.cells;
    if (result.roadsKept) simplification.deadEndAngle = 0.0;
    IntersectionSimplificationStats s = simplifyIntersections(graph, simplification, p);
    result.deadEndRemovedLinks = std::move(s.removedLinks);
    return counts(s.deadEndsRemoved, " dead ends removed, ", s.nodesContracted, " nodes contracted, ",
                  s.contractionsKept, " contractions left out to keep road cells covered, ",
                  s.intersectionsMerged, " intersections merged");
  });
  run("B6", "curve smoothing", 0.12, true, [&](const Progress& p) {
    CurveSmoothingOptions curves = options.curves;
    curves.threads = options.city.parcels.threads;
    if (options.keepRoadCellsCovered) curves.coverCells = &result.cells;
    const CurveSmoothingStats s = smoothCurves(graph, curves, p);
    return counts(s.bends, " bends, ", s.nodesInserted, " nodes inserted, ", s.passes, " passes");
  });
  run("B7", "through roads", 0.03, true, [&](const Progress& p) {
    ThroughRoadOptions through = options.throughRoads;
    through.threads = options.city.parcels.threads;
    if (options.keepRoadCellsCovered) {
      through.cells = &result.cells;
      through.coverRadius = options.curves.coverRadius;
    }
    const ThroughRoadStats s = straightenThroughRoads(graph, through, p);
    if (!options.throughRoads.enabled) return std::string("skipped");
    return counts(s.clusters, " junction clusters, ", s.clustersConsolidated, " consolidated (",
                  s.junctionsRemoved, " junctions fewer, ", s.clustersNudged, " nudged to cover), ",
                  s.intersections, " intersections, ", s.pairs, " through pairs, ", s.nodesPlaced,
                  " nodes placed, ", s.outOfReach, " out of reach, ", s.approaches, " approaches, ",
                  s.straightChains, " straight roads, ", s.crossingsAvoided,
                  " moves left out for crossings, ", s.uncoveringAvoided, " for uncovered cells");
  });
  run("F", "road output", 0.05, false, [&](const Progress& p) {
    std::size_t noded = 0;
    if (options.planarize) {
      noded = nodeCrossingsAndContractTinyLinks(graph);
      // [INFERENCE] Loops that B5/B6 collapsed onto a line (doubled roads enclosing nothing) go too.
      CycleRemovalOptions degenerate;
      degenerate.maxCycleNodes = std::numeric_limits<int>::max();
      degenerate.maxFaceArea = 1e-4;
      degenerate.threads = options.city.parcels.threads;
      removeShortCycles(graph, degenerate);
      noded += nodeCrossingsAndContractTinyLinks(graph);
    }
    reportProgress(p, 0.5, "road output");
    // The simplified network and, when it is simplified, the exact one, side by side: one walk of the
    // graph for both (its planar graph is gone before the simplifier builds its index).
    const bool simplified = options.outputSimplification > 0;
    result.network = buildRoadNetwork(graph);
    // Nothing reads the graph after this walk: it goes before the simplifier builds its index (about a
    // hundred bytes a node), unless the caller keeps it.
    if (!options.keepRoadGraph) {
      releasedGraphCounts.emplace(graph.aliveCount(), graph.linkCount());
      graph = RoadGraph();
      releaseFreedMemory();
    }
    RoadNetwork exact;
    if (simplified) {
      exact = result.network;
      simplifyRoadNetwork(result.network, options.outputSimplification);
    }
    std::size_t restored = 0, uncovering = 0;
    if (simplified) {
      uncovering = restoreUncoveringSegments(result.network, exact, input.landUse, result.cells,
                                             options.outputSimplification);
      restored = restoreTouchingSegments(result.network, exact);
    }
    const CurveDrawingStats curves =
        drawCurves(result.network, input.landUse, result.cells, options.curveDrawing);
    std::vector<Layer> layers = roadLayers(result.network, input.spec);
    const std::size_t segments = layers[0].features.size();
    for (Layer& l : layers) emit(std::move(l));
    return counts(noded, " crossings noded, ", segments, " road segments, ", restored,
                  " kept unsimplified (touching another), ", uncovering,
                  " simplified less (uncovering a road cell), ", curves.segments, " drawn with curves (",
                  curves.points, " spline points), ", curves.restored, " kept as polylines");
  });
  releaseFreedMemory();
  if (!options.roadsOnly) {
    const auto t0 = std::chrono::steady_clock::now();
    resetPeakMemory();
    CityOptions city = options.city;
    city.originCol = input.originCol;
    city.originRow = input.originRow;
    city.blocks.external.undeveloped = options.perimeters;
    result.city = vectorizeCity(result.network, result.cells, result.blocks, result.parcels, input.spec, city,
                                subProgress(progress, 0.3, 1.0), emit);
    StageReport report;
    report.id = "C-E";
    report.name = "pavement, blocks, spines, parcels";
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    report.peakMemoryKb = peakMemoryKb();
    std::size_t parcelCount = 0;
    for (const auto& b : result.city.parcels.blocks) parcelCount += b.parcels.size();
    report.summary = counts(result.city.blockFeatures, " blocks, ", parcelCount, " parcels, ",
                            result.city.blocks.stats.failsafeUses, " failsafe matches (",
                            result.city.blocks.stats.failsafeWithParcels, " with parcels), ",
                            result.city.blocks.stats.overlapUses, " by cell overlap, ",
                            result.city.blocks.stats.underPavement, " left under pavement");
    result.stages.push_back(report);
    populationWarnings(population, result);
  }
  reportProgress(progress, 1.0, "done");
  return result;
}

}  // namespace

VectorizeResult vectorize(const VectorizeInput& input, const VectorizeOptions& options,
                          const Progress& progress) {
  return runPipeline(input, nullptr, options, progress, {});
}

VectorizeResult vectorizeReleasingInput(VectorizeInput& input, const VectorizeOptions& options,
                                        const Progress& progress, const LayerSink& sink) {
  return runPipeline(input, &input, options, progress, sink);
}

}  // namespace urbanvec::vectorize
