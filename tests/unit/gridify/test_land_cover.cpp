// A land-cover source in gridify (issue 20, docs/gridify.md "Land-cover raster"): the priority order
// land-use polygon > land cover > block inference, buildings taking the land cover's class, and the
// land cover reaching land outside the street network too.
#include <gtest/gtest.h>

#include "urbanvec/core/error.hpp"
#include "urbanvec/gridify/gridify.hpp"

using namespace urbanvec;
using namespace urbanvec::gridify;

namespace {

// 96 m x 96 m of 8 m cells (12 x 12); streets at 20, 52 and 84 m both ways make four inner blocks.
Polygon rect(double x0, double y0, double x1, double y1) {
  return {{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, {}};
}

CityData city() {
  CityData c;
  for (double v : {20.0, 52.0, 84.0}) {
    c.roads.push_back({{{v, 0.0}, {v, 96.0}}, LandUse::SecondaryRoad, "tertiary", ""});
    c.roads.push_back({{{0.0, v}, {96.0, v}}, LandUse::SecondaryRoad, "tertiary", ""});
  }
  return c;
}

GridifyOptions options() {
  GridifyOptions o;
  o.cellSize = 8.0;
  o.extent = Extent{0.0, 0.0, 96.0, 96.0};
  return o;
}

LandUse at(const GridifyResult& r, double x, double y) {
  return static_cast<LandUse>(r.landUse.at(static_cast<int>(x / 8.0), static_cast<int>((96.0 - y) / 8.0)));
}

void paint(Grid<std::uint8_t>& g, double x0, double y0, double x1, double y1, LandUse use) {
  for (int r = 0; r < g.height; ++r)
    for (int c = 0; c < g.width; ++c) {
      const double x = c * 8.0 + 4.0, y = 96.0 - r * 8.0 - 4.0;
      if (x > x0 && x < x1 && y > y0 && y < y1) g.at(c, r) = static_cast<std::uint8_t>(use);
    }
}

}  // namespace

TEST(LandCover, PolygonsWinThenTheLandCoverThenTheInference) {
  CityData c = city();
  c.areas.push_back({{rect(20, 52, 52, 84)}, LandUse::Commercial});             // north-west block, tagged
  c.buildings.push_back({{rect(62, 30, 74, 42)}, std::nullopt, std::nullopt});  // south-east block
  c.landCover = Grid<std::uint8_t>(12, 12, static_cast<std::uint8_t>(LandUse::Unused));
  paint(c.landCover, 0, 52, 96, 96, LandUse::Industrial);  // the northern half, over the tagged block
  paint(c.landCover, 52, 20, 84, 52, LandUse::Park);       // the south-east block
  const GridifyResult r = gridify::gridify(c, options());

  EXPECT_EQ(at(r, 36, 68), LandUse::Commercial);  // under the polygon: the land cover does not reach it
  EXPECT_EQ(at(r, 68, 68), LandUse::Industrial);  // untagged, inside: the land cover's class
  EXPECT_EQ(at(r, 8, 92), LandUse::Industrial);   // outside the street network: the land cover still tells
  EXPECT_EQ(at(r, 68, 36), LandUse::Park);        // the building with no use of its own takes the cover's
  EXPECT_EQ(at(r, 60, 28), LandUse::Park);
  EXPECT_EQ(at(r, 36, 36), LandUse::Residential);  // no cover: the inference (-default-use)
  EXPECT_EQ(at(r, 8, 8), LandUse::Unused);         // no cover, outside: unused
  // 69 painted cells (60 north, 9 south-east) less the 16-25 under the polygon (its edges run along
  // the cell centres of the streets, where the rasterization may count them either way).
  EXPECT_GE(r.landCoverCells, 44u);
  EXPECT_LE(r.landCoverCells, 53u);

  // Without the land cover the building is residential (the default building use) and so its block.
  CityData plain = c;
  plain.landCover = {};
  const GridifyResult p = gridify::gridify(plain, options());
  EXPECT_EQ(at(p, 68, 36), LandUse::Residential);
  EXPECT_EQ(at(p, 68, 68), LandUse::Residential);
  EXPECT_EQ(at(p, 8, 92), LandUse::Unused);
  EXPECT_EQ(p.landCoverCells, 0u);
}

TEST(LandCover, ALandCoverOffTheGridIsAnInternalError) {
  CityData c = city();
  c.landCover = Grid<std::uint8_t>(11, 12, static_cast<std::uint8_t>(LandUse::Industrial));
  EXPECT_THROW(gridify::gridify(c, options()), Error);
}
