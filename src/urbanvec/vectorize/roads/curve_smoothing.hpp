// Stage B6 — curve smoothing (spec §3 B6; thesis §3.2.6, paper §3.2.2): nodes are inserted where the
// road bends sharply (3/2/1 per side below 90/135/160 degrees) so eight averaging passes smooth the
// staircase without flattening real curves.
#pragma once

#include "urbanvec/core/progress.hpp"
#include "urbanvec/vectorize/roads/road_graph.hpp"
#include "urbanvec/vectorize/roads/road_smoothing.hpp"

namespace urbanvec::vectorize {

struct CurveSmoothingOptions {
  /// Averaging passes after the insertion.
  int passes = 8;
  /// Interior angle below which 3 nodes are added on each side of the bend, in degrees.
  double angleThreeNodes = 90.0;
  /// Interior angle below which 2 nodes are added on each side, in degrees.
  double angleTwoNodes = 135.0;
  /// Interior angle below which 1 node is added on each side, in degrees.
  double angleOneNode = 160.0;
  /// Largest distance a node may end up from the cells it was placed for, in pw
  /// (kDefaultSmoothingReach); an inserted node is placed on the line between its link ends' placements.
  double reach = kDefaultSmoothingReach;
  /// [INFERENCE, beyond the documents] As RoadSmoothingOptions::coverCells / coverRadius (pw).
  const Grid<std::uint8_t>* coverCells = nullptr;
  double coverRadius = 1.5;
  /// Worker threads of the averaging passes; 0 = all cores. Does not change the output.
  int threads = 0;
};

struct CurveSmoothingStats {
  std::size_t bends = 0;  ///< nodes whose angle triggered an insertion
  std::size_t nodesInserted = 0;
  int passes = 0;  ///< averaging passes run
};

/// Nodes to add on each side of a bend with interior angle `degrees` (180 = straight).
int curveInsertionCount(double degrees, const CurveSmoothingOptions& options);

CurveSmoothingStats smoothCurves(RoadGraph& graph, const CurveSmoothingOptions& options,
                                 const Progress& progress = {});

}  // namespace urbanvec::vectorize
