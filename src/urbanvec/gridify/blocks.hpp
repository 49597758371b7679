// Truth blocks: faces of the noded road network, minus water (issue 2 §2 `truth.gpkg` "blocks").
#pragma once

#include <vector>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/gridify/city_data.hpp"

namespace urbanvec::gridify {

struct TruthBlock {
  Polygon shape;
  /// True when the face touches the extent's border (the network does not close it).
  bool external = false;
};

/// The road centrelines (already clipped to the extent) and the extent's border are noded and
/// polygonized; water is cut out; pieces smaller than minArea (m²) are dropped.
std::vector<TruthBlock> roadBlocks(const MultiLineString& roads, const Extent& box,
                                   const std::vector<MultiPolygon>& water, double minArea);

/// The land between the curbs: each block minus the road corridors (each centreline buffered by its
/// half-width in metres, round ends), the way the vectorizer's curbs bound its blocks (spec C: curbs at
/// 1 cell for primary, 0.5 cell for secondary roads). Pieces smaller than minArea (m²) are dropped;
/// a face a corridor cuts in two gives two blocks. A piece is external when it touches the extent's
/// border: corridors close the small gaps centrelines leave (ends meeting a road's side), so a piece
/// of an open face can be enclosed by road surface.
std::vector<TruthBlock> curbBlocks(const std::vector<TruthBlock>& faces, const MultiLineString& roads,
                                   const std::vector<double>& halfWidths, const Extent& box, double minArea);

}  // namespace urbanvec::gridify
