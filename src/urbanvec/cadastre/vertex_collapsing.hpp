// Vertex cleaning by collapsing with the anti-drift rule (spec pueyo-urban-data.md §A.4, Fig. 10).
#pragma once

#include <vector>

#include "urbanvec/cadastre/linework.hpp"
#include "urbanvec/core/progress.hpp"

namespace urbanvec::cadastre {

struct CollapseStats {
  std::size_t inputVertices = 0;     ///< vertex occurrences of all polylines
  std::size_t distinctVertices = 0;  ///< distinct coordinates among them
  std::size_t outputVertices = 0;    ///< representatives after collapsing
  std::size_t reverted = 0;          ///< collapses undone by the anti-drift rule
  std::size_t zeroLengthSegments = 0;
  /// Share of vertex occurrences merged into another (Table 1 "collapsed vertices").
  double collapsedShare() const {
    return inputVertices ? 1.0 - static_cast<double>(outputVertices) / static_cast<double>(inputVertices)
                         : 0.0;
  }
};

/// Collapses the polylines' vertices (layer by layer, polyline by polyline, as given): identical
/// coordinates are one vertex; a vertex closer than `threshold` to a representative joins it when every
/// original coordinate the representative stands for is closer than `threshold` too (the anti-drift
/// rule), and the representative moves to their mean; otherwise the collapse is reverted — the
/// farthest original is split off as its own vertex and the new vertex stays apart. Beyond the thesis,
/// two vertices joined by a segment never collapse together (a short edge of a clean drawing is kept,
/// not shrunk to a point). Returns the representatives and one segment per polyline step (steps that
/// collapsed to a point are dropped and counted). With `revert` false the failed collapse only keeps
/// the new vertex apart and leaves the representative whole (the default, see CadastreOptions). With
/// `freeEndsOnly`, two vertices where lines already meet exactly never collapse together: only a free
/// end (one segment) joins another vertex, so a clean drawing keeps every vertex however close.
/// With `closestFirst` (beyond the thesis) the order of the drawing no longer matters: the pairs of
/// coordinates closer than `threshold` (each coordinate's 24 nearest) are taken closest first, and two
/// vertices merge unless a segment joins them, both are sound (`freeEndsOnly`), or two of their
/// coordinates would end up `threshold` or more apart (the anti-drift rule; counted as reverted).
/// The representative is the mean of its coordinates.
Linework collapseVertices(const std::vector<CadLine>& lines, double threshold, CollapseStats& stats,
                          const Progress& progress = {}, bool revert = true, bool freeEndsOnly = false,
                          bool closestFirst = false);

}  // namespace urbanvec::cadastre
