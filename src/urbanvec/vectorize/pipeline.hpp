// The whole vectorizer, in the order of the stage list of Sexton's thesis (§1 of the spec): pipeline.cpp
// runs A1-A5 and B1-B6 (roads/ and the simulated blocks and parcels), then C-E through city_pipeline
// (pavement/, blocks/, parcels/). docs/architecture.md says which folder holds which stage.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "urbanvec/core/layer.hpp"
#include "urbanvec/core/progress.hpp"
#include "urbanvec/vectorize/blocks/raw_blocks.hpp"
#include "urbanvec/vectorize/city_pipeline.hpp"
#include "urbanvec/vectorize/parcels/parcel_loading.hpp"
#include "urbanvec/vectorize/roads/curve_drawing.hpp"
#include "urbanvec/vectorize/roads/curve_smoothing.hpp"
#include "urbanvec/vectorize/roads/cycle_removal.hpp"
#include "urbanvec/vectorize/roads/intersection_simplification.hpp"
#include "urbanvec/vectorize/roads/patch_cleaning.hpp"
#include "urbanvec/vectorize/roads/perimeters.hpp"
#include "urbanvec/vectorize/roads/road_connection.hpp"
#include "urbanvec/vectorize/roads/road_graph_build.hpp"
#include "urbanvec/vectorize/roads/road_network.hpp"
#include "urbanvec/vectorize/roads/road_smoothing.hpp"
#include "urbanvec/vectorize/roads/straightening.hpp"
#include "urbanvec/vectorize/roads/through_roads.hpp"
#include "urbanvec/vectorize/vectorize_input.hpp"

namespace urbanvec::vectorize {

/// Which of the roads the documents remove on purpose go (A3 the secondary strips beside a primary,
/// B4 a segment of every short cycle, B5 dead ends near another road; docs/vectorize.md "Keeping every
/// road"). On a simulator's grid they are artefacts; on a grid rasterized from mapped streets they are
/// mostly real roads (service roads, slip roads, carriageways beside a primary, loops of lanes).
enum class RoadRemovals {
  Auto,   ///< None when VectorizeInput::roadsFromMappedStreets, else Paper
  Paper,  ///< the documents' removals, as cleanIntersectionPatches, cycles and intersections set them
  /// [beyond the documents] keep every road the grid shows: no A3, no B5 dead-end removal, and B4
  /// removes only loops enclosing no land cell (CycleRemovalOptions::keepLandCycles: where a street
  /// crosses a primary's staircase its cells beside the primary draw such loops).
  None,
};

struct VectorizeOptions {
  RawBlockOptions rawBlocks;  ///< A2
  /// The road removals of A3, B4 and B5 (see RoadRemovals); Auto reads the grid's origin.
  RoadRemovals roadRemovals = RoadRemovals::Auto;
  /// A3 extraneous intersection patch cleaning. false keeps every secondary patch (beyond the
  /// documents): on grids rasterized from mapped streets the strips A3 removes beside a primary are
  /// mostly real service roads, slip roads and parallel carriageways (docs/vectorize.md, "Keeping
  /// every road").
  bool cleanIntersectionPatches = true;
  PatchCleaningOptions patchCleaning;
  RoadGraphOptions roadGraph;          ///< A4.1–A4.7
  PerimeterOptions perimeters;         ///< A4.8
  ParcelLoadingOptions parcelLoading;  ///< A5
  StraighteningOptions straightening;  ///< B1
  RoadSmoothingOptions roadSmoothing;  ///< B2
  RoadConnectionOptions connection;    ///< B3
  CycleRemovalOptions cycles;          ///< B4
  /// B4 with Q10's "undeveloped only" flag: short cycles around developed land keep their roads
  /// (CycleRemovalOptions::landUse); false = the documents' rule on every short cycle.
  bool keepDevelopedCycles = true;
  IntersectionSimplificationOptions intersections;  ///< B5
  CurveSmoothingOptions curves;                     ///< B6
  ThroughRoadOptions throughRoads;                  ///< B7 (issue 20, beyond the documents)
  /// [INFERENCE, beyond the documents] B2 and B6 cut back averaging moves, and B5 leaves out
  /// contractions, that would uncover road cells (RoadSmoothingOptions::coverCells,
  /// IntersectionSimplificationOptions::coverCells); false = the documents' rules (smoothing bounded
  /// only by the smoothing reach).
  bool keepRoadCellsCovered = true;
  /// [INFERENCE] Node crossing links and contract zero-length links after B6, so segments meet only
  /// at shared nodes (the output contract); false = leave the B6 graph as it is.
  bool planarize = true;
  /// [INFERENCE, output only] Tolerance of the topology-preserving simplification of the output road
  /// segments, in pw (0 = every graph node becomes a vertex). The graph keeps its nodes; this removes
  /// the sub-cell wiggle left by smoothing a staircase, which otherwise dominates the turning per km.
  double outputSimplification = 0.3;
  /// [INFERENCE, output only, issue 20] Curved pieces of the simplified segments drawn on the spline
  /// through their vertices (roads/curve_drawing.hpp); tolerance 0 = the polylines as simplified.
  CurveDrawingOptions curveDrawing;
  /// Stages C-E (pavement, blocks, spines, parcels, land use, population).
  CityOptions city;
  /// Stop after the road network (stages A-B): only roads and road_nodes are produced.
  bool roadsOnly = false;
  /// Keep a copy of the road graph after every graph stage (for -debug-stages).
  bool keepStageGraphs = false;
  /// Keep VectorizeResult::roads, the road graph, after F; false releases it once the road network is
  /// built (it is not an output, and at city scale it holds about a hundred bytes a node).
  bool keepRoadGraph = false;
};

/// What one stage did and cost.
struct StageReport {
  std::string id;    ///< "A4", "B1" ...
  std::string name;  ///< "road graph", "intersection straightening" ...
  double seconds = 0;
  long peakMemoryKb =
      -1;                 ///< peak resident memory during the stage (Linux, core/memory.hpp), -1 when unknown
  std::size_t nodes = 0;  ///< road graph nodes after the stage
  std::size_t links = 0;
  std::string summary;  ///< counts the stage reports, one line
};

struct VectorizeResult {
  /// The road removals resolved to None (RoadRemovals, keepsAllRoads).
  bool roadsKept = false;
  /// Land-use codes after cleaning (kRemovedRoad where A3/A4.3 removed road).
  Grid<std::uint8_t> cells;
  std::vector<SimBlock> blocks;  ///< A2 simulated blocks, with their parcels (A5)
  /// Block index per patch, -1 where none (A2); released (left 0 x 0) after A5, the last stage reading it.
  Grid<std::int32_t> blockOf;
  std::vector<SimParcel> parcels;  ///< A5 simulated parcels
  /// The road graph after B7 (and planarization), internal frame (pw); empty unless
  /// VectorizeOptions::keepRoadGraph.
  RoadGraph roads;
  /// Its segments and segment-end nodes (the part 1 -> part 2 interface), output simplification applied.
  RoadNetwork network;
  std::vector<StageReport> stages;
  /// (stage id + name, graph) after each graph stage when keepStageGraphs.
  std::vector<std::pair<std::string, RoadGraph>> stageGraphs;
  /// The road links B4 removed (short cycles), as they lay when removed, internal frame: the roads the
  /// pipeline dropped on purpose, for checkRoadCoverage (road_checks.hpp).
  std::vector<std::array<Vec2, 2>> cycleRemovedLinks;
  /// Links of the dead ends B5 removed (internal frame), for the same check.
  std::vector<std::array<Vec2, 2>> deadEndRemovedLinks;
  std::vector<std::string> warnings;
  /// Stages C-E (empty when roadsOnly); its layers are moved into `layers` (city.layers is left empty).
  CityResult city;
  /// Output layers in world coordinates: roads, road_nodes, then (unless roadsOnly) pavement, blocks,
  /// water, spines, parcels, vectorize_report.
  std::vector<Layer> layers;
};

/// Whether `removals` keeps every road of `input` (None, or Auto on a grid from mapped streets).
bool keepsAllRoads(RoadRemovals removals, const VectorizeInput& input);

/// Runs the pipeline. Throws urbanvec::Error (InvalidInput) on inconsistent input and Cancelled when
/// the progress callback asks to stop.
VectorizeResult vectorize(const VectorizeInput& input, const VectorizeOptions& options,
                          const Progress& progress = {});

/// The same run, which also frees `input`'s density and parcel grids and its parcel table once A5 has
/// read them (8 bytes a cell: on a city-sized grid more than the output). The rest of `input` (spec,
/// landUse, openRegions) stays for the caller.
///
/// With a `sink`, each output layer goes to it as soon as it is final, in the order of
/// VectorizeResult::layers (roads and road_nodes at the end of F, pavement once E's road frontage has
/// read it, the rest at the end), instead of into `layers`, which is then left empty.
VectorizeResult vectorizeReleasingInput(VectorizeInput& input, const VectorizeOptions& options,
                                        const Progress& progress = {}, const LayerSink& sink = {});

}  // namespace urbanvec::vectorize
