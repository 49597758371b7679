// Small land-use grids drawn as text for the vectorizer's unit tests.
#pragma once

#include <string>
#include <vector>

#include "urbanvec/core/landuse.hpp"
#include "urbanvec/vectorize/vectorize_input.hpp"

namespace urbanvec::vectorize::testing {

/// '.' unused, 'w' water, 's' secondary road, 'P' primary road, 'r' residential, 'c' commercial,
/// 'i' industrial, 'k' park, 'x' reserved. Row 0 is the first (northern) string.
inline Grid<std::uint8_t> drawGrid(const std::vector<std::string>& rows) {
  Grid<std::uint8_t> g(static_cast<int>(rows[0].size()), static_cast<int>(rows.size()), 0);
  for (int r = 0; r < g.height; ++r)
    for (int c = 0; c < g.width; ++c) {
      LandUse u = LandUse::Unused;
      switch (rows[r][c]) {
        case 'w': u = LandUse::Water; break;
        case 's': u = LandUse::SecondaryRoad; break;
        case 'P': u = LandUse::PrimaryRoad; break;
        case 'r': u = LandUse::Residential; break;
        case 'c': u = LandUse::Commercial; break;
        case 'i': u = LandUse::Industrial; break;
        case 'k': u = LandUse::Park; break;
        case 'x': u = LandUse::Reserved; break;
        default: break;
      }
      g.at(c, r) = static_cast<std::uint8_t>(u);
    }
  return g;
}

/// A VectorizeInput over a drawn grid with a north-up 10 m geotransform at (1000, 2000).
inline VectorizeInput drawInput(const std::vector<std::string>& rows) {
  VectorizeInput in;
  in.landUse = drawGrid(rows);
  in.spec.width = in.landUse.width;
  in.spec.height = in.landUse.height;
  in.spec.transform.c = {1000.0, 10.0, 0.0, 2000.0, 0.0, -10.0};
  return in;
}

/// A grid of w x h cells with the given fill, to draw roads on with setCells.
inline std::vector<std::string> blank(int w, int h, char fill = 'r') {
  return std::vector<std::string>(static_cast<size_t>(h), std::string(static_cast<size_t>(w), fill));
}

}  // namespace urbanvec::vectorize::testing
