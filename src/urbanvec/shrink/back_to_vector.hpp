// Step 8Pos of the shrinking pipeline (spec §B.11): node positions after carving. A node moves by
// exactly c_size times the pixels its pixel moved towards lower indices (x' = x - c_size (i - i'),
// the sign-corrected formula); a node whose pixel a seam removed is deleted (the thesis) or, when
// `collapse` is set (full map, keepCarvedNodes), put on the edge of the neighbour its pixel collapsed
// onto.
#pragma once

#include "urbanvec/shrink/rasterise.hpp"
#include "urbanvec/shrink/seam_carving.hpp"

namespace urbanvec::shrink {

class PointMapper {
 public:
  PointMapper(const RasterFrame& frame, const CarveResult& carve) : frame_(frame), carve_(carve) {}
  /// The position of p after carving; false when its pixel was removed and !collapse.
  bool map(const Vec2& p, bool collapse, Vec2& out) const;
  /// True when the pixel of p survived every seam.
  bool survives(const Vec2& p) const;
  /// Centre, in the original frame, of an original pixel index.
  Vec2 pixelCentre(int pixel) const;

 private:
  const RasterFrame& frame_;
  const CarveResult& carve_;
};

/// The ways (point lists into `pos`) in pixel units of `frame`, each point in its pixel and at its
/// place inside it as PointMapper reads them: the crossing guard's input (carveSeams).
SeamWays seamWaysOf(const std::vector<std::vector<int>>& ways, const std::vector<Vec2>& pos,
                    const RasterFrame& frame);

}  // namespace urbanvec::shrink
