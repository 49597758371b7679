// Stage A4.8 — external block perimeters (spec §3 A4.8, §9.1 Q7; thesis §3.1.4, paper §3.2.1):
// staircase lines along patch edges that separate undeveloped land from external blocks, added to the
// road graph as Perimeter nodes (connected to the roads later, in B3).
#pragma once

#include <cstdint>
#include <vector>

#include "urbanvec/core/grid.hpp"
#include "urbanvec/core/progress.hpp"
#include "urbanvec/vectorize/roads/road_graph.hpp"
#include "urbanvec/vectorize/vectorize_input.hpp"

namespace urbanvec::vectorize {

struct PerimeterOptions {
  /// Treat water next to an external block as undeveloped land (Q7, [INFERENCE]); cells outside the
  /// grid always count as undeveloped.
  bool waterIsUndeveloped = true;
  /// [INFERENCE] Treat reserved land that belongs to no block (A2 excludes it by default) as
  /// undeveloped too: otherwise a perimeter stops where the undeveloped edge meets reserved land and
  /// the external block it bounds never closes (D4).
  bool reservedIsUndeveloped = true;
};

struct PerimeterStats {
  std::size_t lines = 0;        ///< perimeter lines added
  std::size_t closedLoops = 0;  ///< closed loops without an end, skipped (spec: "log them")
};

/// Adds the perimeter lines of the external blocks (blockOf, blocks from A2) to `graph`.
PerimeterStats addExternalPerimeters(RoadGraph& graph, const Grid<std::uint8_t>& cells,
                                     const Grid<std::int32_t>& blockOf, const std::vector<SimBlock>& blocks,
                                     const PerimeterOptions& options, const Progress& progress = {});

}  // namespace urbanvec::vectorize
