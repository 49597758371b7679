// Stage B4 — cycle removal (spec §3 B4, §9.2 Q10; thesis §3.2.4, paper §3.2.2): road cycles of at most
// 15 nodes enclose land too small to develop; one road segment of each is removed.
#pragma once

#include <array>
#include <vector>

#include "urbanvec/core/grid.hpp"
#include "urbanvec/core/progress.hpp"
#include "urbanvec/vectorize/roads/road_graph.hpp"

namespace urbanvec::vectorize {

struct CycleRemovalOptions {
  /// Bounded faces with at most this many distinct cycle nodes lose one segment.
  int maxCycleNodes = 15;
  /// Only faces enclosing at most this area count, in pw^2 (the documents set no limit; the pipeline's
  /// final clean-up uses a tiny value to drop loops that smoothing collapsed onto a line).
  double maxFaceArea = 1e300;
  /// [INFERENCE] Node crossing links first, so the face walk runs on a planar embedding (smoothing in
  /// B1/B2 can twist small loops into self-crossing slivers the walk would not see as faces).
  bool planarizeFirst = true;
  /// Safety cap on the repeat-until-none rounds (each round removes one segment per disjoint face).
  int maxRounds = 64;
  /// Q10 flag: with a land-use grid (LandUse codes, internal frame of the graph), a face keeps its
  /// roads when a cell centre it encloses is developed land (residential, commercial, industrial,
  /// park). The documents motivate B4 by "undeveloped land which is awkward to develop"; removing a
  /// road around a developed block merges it into its neighbour. Null = the documents' rule on every
  /// short face.
  const Grid<std::uint8_t>* landUse = nullptr;
  /// With landUse: a face keeps its roads when it encloses any land cell centre (any cell that is not
  /// road: developed, unused, water, reserved), not only developed land. Only loops drawn around road
  /// cells alone go: where a street crosses a primary's staircase, its cells beside the primary make
  /// such loops, and a loop of real roads on a grid always holds land between them (the road-removal
  /// mode `none` of grids rasterized from mapped streets, docs/vectorize.md "Keeping every road").
  bool keepLandCycles = false;
  /// With keepLandCycles, only faces enclosing at most this area go, in pw^2: the cells where a
  /// 1-wide street crosses a 2-wide primary (a 2 x 2 window and the steps of the street's staircase
  /// beside it). Longer loops around road cells alone are carriageways side by side in a band of road
  /// cells, real roads (measured in docs/vectorize.md, "Keeping every road").
  double landlessFaceArea = 4.0;
  /// Worker threads of the per-face tests and link sorting (0 = all cores). Does not change the output.
  int threads = 0;
};

struct CycleRemovalStats {
  std::size_t segmentsRemoved = 0;
  std::size_t rounds = 0;
  std::size_t crossingsNoded = 0;      ///< by planarizeFirst
  std::size_t developedFacesKept = 0;  ///< short faces kept because they enclose developed land (Q10)
  /// Every link removed, as it lay when removed (internal frame): what was dropped on purpose, for the
  /// road-cell coverage check (road_checks.hpp).
  std::vector<std::array<Vec2, 2>> removedLinks;
};

/// Faces come from the leftmost-turn walk over the clockwise-sorted road-only graph (perimeter links
/// are not road and never removed). The removed segment is the shortest chain between nodes of
/// degree other than 2 along the face, secondary chains preferred over primary.
CycleRemovalStats removeShortCycles(RoadGraph& graph, const CycleRemovalOptions& options,
                                    const Progress& progress = {});

/// Bounded faces of the road-only graph, each as its cycle (spur edges dropped), counter-clockwise.
/// Exposed for tests and checks.
std::vector<std::vector<int>> boundedRoadFaces(const RoadGraph& graph);

}  // namespace urbanvec::vectorize
