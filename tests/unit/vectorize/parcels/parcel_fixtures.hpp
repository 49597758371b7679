// Synthetic blocks for the part-3 tests: rectangles (optionally rotated, with a jittered ~1-cell
// boundary like smoothed curbs) whose simulated parcels come from a random guillotine partition of the
// block's cells.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "urbanvec/core/geometry.hpp"
#include "urbanvec/io/vector_io.hpp"
#include "urbanvec/vectorize/parcels/parcel_input.hpp"
#include "urbanvec/vectorize/parcels/spines.hpp"

namespace urbanvec::vectorize::parcels::fixtures {

/// Readable names for tests parameterized by spine method.
inline std::string methodName(const ::testing::TestParamInfo<SpineMethod>& info) {
  return info.param == SpineMethod::Skeleton ? "Skeleton" : "ZhangSuen";
}

inline Ring rectangleRing(double w, double h) {
  return {{0, 0}, {w, 0}, {w, h}, {0, h}, {0, 0}};
}

/// A w×h rectangle block, every edge road-facing, with `uses[k]` simulated parcels of equal width
/// laid out along the long side, `populationEach` people each.
inline ParcelBlock stripBlock(int w, int h, const std::vector<LandUse>& uses, double populationEach = 10.0) {
  ParcelBlock b;
  b.polygon.outer = rectangleRing(w, h);
  b.roadFacing = {b.polygon.outer};
  b.sim.area = w * h;
  b.sim.developedArea = w * h;
  const int n = static_cast<int>(uses.size());
  const double width = static_cast<double>(w) / n;
  for (int k = 0; k < n; ++k) {
    SimParcel p;
    p.id = k + 1;
    p.use = uses[k];
    p.cells = width * h;
    p.population = populationEach;
    p.centre = {width * (k + 0.5), h / 2.0};
    b.sim.parcels.push_back(p);
  }
  return b;
}

/// A random block: w×h cells partitioned into simulated parcels (guillotine cuts on whole cells down
/// to `minSide` cells), a share of cells left unused, rotated by `angle` and with the boundary
/// subdivided into 1-cell edges jittered by up to `jitter` cells perpendicular to the edge.
inline ParcelBlock randomBlock(std::int64_t id, int w, int h, double angle, double jitter, double unusedShare,
                               std::mt19937_64& rng) {
  ParcelBlock b;
  b.blockId = id;
  struct Rect {
    int x0, y0, x1, y1;
  };
  std::vector<Rect> rects{{0, 0, w, h}}, done;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int minSide = 2;
  while (!rects.empty()) {
    Rect r = rects.back();
    rects.pop_back();
    const int rw = r.x1 - r.x0, rh = r.y1 - r.y0;
    if ((rw < 2 * minSide && rh < 2 * minSide) || (rw * rh <= 12 && unit(rng) < 0.6)) {
      done.push_back(r);
      continue;
    }
    if (rw >= rh && rw >= 2 * minSide) {
      const int cut = r.x0 + minSide + static_cast<int>(unit(rng) * (rw - 2 * minSide + 1));
      rects.push_back({r.x0, r.y0, cut, r.y1});
      rects.push_back({cut, r.y0, r.x1, r.y1});
    } else {
      const int cut = r.y0 + minSide + static_cast<int>(unit(rng) * (rh - 2 * minSide + 1));
      rects.push_back({r.x0, r.y0, r.x1, cut});
      rects.push_back({r.x0, cut, r.x1, r.y1});
    }
  }
  const Vec2 u{std::cos(angle), std::sin(angle)}, v{-std::sin(angle), std::cos(angle)};
  auto place = [&](double x, double y) { return u * x + v * y; };
  const LandUse developed[] = {LandUse::Residential, LandUse::Residential, LandUse::Residential,
                               LandUse::Commercial,  LandUse::Industrial,  LandUse::Park};
  b.sim.area = w * h;
  int id2 = 1;
  for (const Rect& r : done) {
    const double cells = (r.x1 - r.x0) * (r.y1 - r.y0);
    if (unit(rng) < unusedShare) {
      b.sim.undevelopedArea += cells;
      continue;
    }
    SimParcel p;
    p.id = id2++;
    p.use = developed[static_cast<int>(unit(rng) * 6) % 6];
    p.cells = cells;
    p.population = p.use == LandUse::Residential ? std::round(cells * 3.0) : 0.0;
    p.centre = place((r.x0 + r.x1) / 2.0, (r.y0 + r.y1) / 2.0);
    b.sim.developedArea += cells;
    b.sim.parcels.push_back(p);
  }
  // Boundary: 1-cell steps, jittered inwards/outwards, corners kept.
  Ring ring;
  const Vec2 corners[] = {{0, 0},
                          {static_cast<double>(w), 0},
                          {static_cast<double>(w), static_cast<double>(h)},
                          {0, static_cast<double>(h)}};
  for (int c = 0; c < 4; ++c) {
    const Vec2 a = corners[c], e = corners[(c + 1) % 4];
    const int steps = static_cast<int>(std::lround(distance(a, e)));
    const Vec2 dir = (e - a) / distance(a, e);
    const Vec2 normal{-dir.y, dir.x};
    for (int s = 0; s < steps; ++s) {
      Vec2 p = a + dir * static_cast<double>(s);
      if (s > 0) p += normal * (jitter * (2.0 * unit(rng) - 1.0));
      ring.push_back(place(p.x, p.y));
    }
  }
  ring.push_back(ring.front());
  b.polygon.outer = ring;
  b.roadFacing = {ring};
  return b;
}

/// The sample's truth blocks in cells of 8 m (both samples' grids) about the blocks' south-west corner,
/// as the pipeline's frame has them: coordinates from 0 to a few hundred, plus `offset` cells (a block
/// in the far corner of a 4096² grid has coordinates near 4000, and larger rounding errors).
inline std::vector<Polygon> sampleBlocks(const std::string& city, double offset = 0.0) {
  const std::string path = std::string(URBANVEC_SOURCE_DIR) + "/sample_data/" + city + "/truth.gpkg";
  const auto read = io::readVectorLayer(path, "blocks", "truth");
  EXPECT_TRUE(read.has_value());
  std::vector<Polygon> blocks;
  if (!read) return blocks;
  double minX = 1e300, minY = 1e300;
  for (const Feature& f : read->layer.features)
    if (const auto* p = std::get_if<Polygon>(&f.geometry))
      for (const Vec2& v : p->outer) {
        minX = std::min(minX, v.x);
        minY = std::min(minY, v.y);
      }
  auto toCells = [&](Ring ring) {
    for (Vec2& v : ring) v = {(v.x - minX) / 8.0 + offset, (v.y - minY) / 8.0 + offset};
    return ring;
  };
  for (const Feature& f : read->layer.features)
    if (const auto* p = std::get_if<Polygon>(&f.geometry)) {
      Polygon cells{toCells(p->outer), {}};
      for (const Ring& h : p->holes) cells.holes.push_back(toCells(h));
      if (area(cells) > 20.0) blocks.push_back(std::move(cells));
    }
  return blocks;
}

}  // namespace urbanvec::vectorize::parcels::fixtures
