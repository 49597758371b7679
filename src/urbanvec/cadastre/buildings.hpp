// Localisation of faces in blocks and building elements (spec pueyo-urban-data.md §A.7).
#pragma once

#include <cstdint>
#include <vector>

#include "urbanvec/core/geometry.hpp"

namespace urbanvec::cadastre {

/// Sub-block polygons indexed for point location (a grid over their boxes).
class BlockLocator {
 public:
  /// `owners[i]` is the block id of `areas[i]`.
  BlockLocator(std::vector<Polygon> areas, std::vector<int> owners);
  /// The block id of the area containing p, or -1 (a street, a courtyard).
  int locate(const Vec2& p) const;

 private:
  std::vector<Polygon> areas_;
  std::vector<int> owners_;
  double cell_ = 1.0;
  std::vector<std::pair<std::int64_t, int>> index_;  ///< (cell key, area), sorted
  std::int64_t key(std::int64_t i, std::int64_t j) const { return i * 2000003LL + j; }
};

/// Polygons with the block each lies in (§A.7 "localisation": by an interior point, as the thesis's
/// per-block processing would), dropping those outside every block.
struct Localised {
  MultiPolygon shape;
  int block = -1;
  Vec2 inside;  ///< the interior point used
};
/// Faces outside every block go to `outsideFaces` (block -1) when given.
std::vector<Localised> localise(const std::vector<Polygon>& faces, const BlockLocator& blocks, double minArea,
                                std::size_t& outside, std::vector<Localised>* outsideFaces = nullptr);

/// Label assignment (§A.8 "point-in-polygon"), with the cases the thesis leaves open: a label outside
/// every polygon goes to the nearest within `searchDistance` (counted in `snapped`, else `unmatched`);
/// a polygon holding several labels keeps the one nearest its interior point (`crowded` polygons).
/// Returns the label index per polygon (-1 = none).
std::vector<int> assignLabels(const std::vector<Localised>& polygons, const std::vector<Vec2>& labels,
                              double searchDistance, std::size_t& snapped, std::size_t& unmatched,
                              std::size_t& crowded);

}  // namespace urbanvec::cadastre
