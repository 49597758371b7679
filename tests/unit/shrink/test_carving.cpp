// Seam carving (spec §B.10, §H.2 item 6) and the energy of §B.9.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>

#include "urbanvec/shrink/energy.hpp"
#include "urbanvec/shrink/seam_carving.hpp"

namespace urbanvec::shrink {
namespace {

const float kInf = std::numeric_limits<float>::infinity();

/// Cheapest 8-connected vertical seam cost by brute force over every path.
double bruteForce(const std::vector<float>& e, int w, int h) {
  double best = std::numeric_limits<double>::infinity();
  std::vector<int> path(static_cast<size_t>(h));
  std::function<void(int, double)> walk = [&](int r, double sum) {
    if (r == h) {
      best = std::min(best, sum);
      return;
    }
    for (int dc = -1; dc <= 1; ++dc) {
      const int c = r == 0 ? dc + 1 : path[static_cast<size_t>(r - 1)] + dc;
      if (r == 0 && dc > 1) continue;
      if (c < 0 || c >= w) continue;
      path[static_cast<size_t>(r)] = c;
      walk(r + 1, sum + e[static_cast<size_t>(r * w + c)]);
    }
  };
  for (int c0 = 0; c0 < w; ++c0) {
    path[0] = c0;
    walk(1, e[static_cast<size_t>(c0)]);
  }
  return best;
}

TEST(SeamCarving, FirstSeamMatchesBruteForceOnRandomImages) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> value(0, 255);
  for (int trial = 0; trial < 40; ++trial) {
    const int w = 3 + trial % 4, h = 3 + (trial / 4) % 4;
    std::vector<float> e(static_cast<size_t>(w * h));
    for (float& v : e) v = static_cast<float>(value(rng));
    const CarveResult r = carveSeams(e, w, h, 1, 0, SeamOrder::Blocks);
    ASSERT_EQ(r.seams.size(), 1u);
    double sum = 0.0;
    for (int px : r.seams[0].pixels) sum += e[static_cast<size_t>(px)];
    EXPECT_DOUBLE_EQ(sum, bruteForce(e, w, h)) << "trial " << trial;
  }
}

TEST(SeamCarving, SizesConnectivityFrozenPixelsAndAlignment) {
  const int w = 40, h = 30;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> value(0.0f, 255.0f);
  std::vector<float> e(static_cast<size_t>(w * h));
  for (float& v : e) v = value(rng);
  // A frozen block and a frozen diagonal line.
  for (int r = 10; r < 14; ++r)
    for (int c = 5; c < 9; ++c) e[static_cast<size_t>(r * w + c)] = kInf;
  for (int k = 0; k < 20; ++k) e[static_cast<size_t>((k + 5) * w + k + 15)] = kInf;
  for (SeamOrder order : {SeamOrder::Blocks, SeamOrder::Interleaved}) {
    const CarveResult r = carveSeams(e, w, h, 12, 9, order);
    EXPECT_EQ(r.width, w - 12);
    EXPECT_EQ(r.height, h - 9);
    EXPECT_EQ(r.verticalRemoved, 12);
    EXPECT_EQ(r.horizontalRemoved, 9);
    for (size_t i = 0; i < e.size(); ++i)
      if (std::isinf(e[i])) EXPECT_GE(r.finalRow[i], 0) << "frozen pixel " << i << " removed";
    // Every final cell holds exactly one original pixel; order within rows and columns is kept.
    std::vector<int> seen(static_cast<size_t>(r.width * r.height), -1);
    int survivors = 0;
    for (size_t i = 0; i < e.size(); ++i) {
      if (r.finalRow[i] < 0) continue;
      ++survivors;
      int& slot = seen[static_cast<size_t>(r.finalRow[i] * r.width + r.finalCol[i])];
      EXPECT_EQ(slot, -1);
      slot = static_cast<int>(i);
      EXPECT_LE(r.finalRow[i], static_cast<int>(i) / w);
      EXPECT_LE(r.finalCol[i], static_cast<int>(i) % w);
    }
    EXPECT_EQ(survivors, r.width * r.height);
    // Blocks order carves columns first, while every original row is still one image row: the pixels of
    // an original row keep their left-right order. (Across rows seams may differ, so the other axis
    // and the interleaved order give no such guarantee: the measures count landmark pairs that flip.)
    for (int row = 0; row < h && order == SeamOrder::Blocks; ++row)
      for (int c = 0, last = -1; c < w; ++c) {
        const int fc = r.finalCol[static_cast<size_t>(row * w + c)];
        if (fc < 0) continue;
        EXPECT_GT(fc, last);
        last = fc;
      }
    // The first seam crosses the whole image, 8-connected.
    const CarvedSeam& s = r.seams[0];
    ASSERT_EQ(static_cast<int>(s.pixels.size()), s.vertical ? h : w);
    for (size_t k = 1; k < s.pixels.size(); ++k) {
      const int a = s.pixels[k - 1], b = s.pixels[k];
      if (s.vertical) {
        EXPECT_EQ(b / w, a / w + 1);
        EXPECT_LE(std::abs(b % w - a % w), 1);
      } else {
        EXPECT_EQ(b % w, a % w + 1);
        EXPECT_LE(std::abs(b / w - a / w), 1);
      }
    }
  }
}

/// The textbook carving: the whole cumulative energy recomputed for every seam, the seam cut out of a
/// copy of the image; same tie rules as carveSeams (lowest end column; straight, left, right). Returns
/// the original pixels of each vertical seam.
std::vector<std::vector<int>> referenceVerticalSeams(const std::vector<float>& e0, int w, int h, int seams) {
  std::vector<float> e = e0;
  std::vector<int> idx(e.size());
  for (size_t i = 0; i < idx.size(); ++i) idx[i] = static_cast<int>(i);
  std::vector<std::vector<int>> out;
  for (int cols = w; seams-- > 0; --cols) {
    std::vector<float> m(static_cast<size_t>(cols * h));
    for (int r = 0; r < h; ++r)
      for (int c = 0; c < cols; ++c) {
        float best = 0.0f;
        if (r > 0) {
          best = m[static_cast<size_t>((r - 1) * cols + c)];
          if (c > 0) best = std::min(best, m[static_cast<size_t>((r - 1) * cols + c - 1)]);
          if (c + 1 < cols) best = std::min(best, m[static_cast<size_t>((r - 1) * cols + c + 1)]);
        }
        m[static_cast<size_t>(r * cols + c)] = e[static_cast<size_t>(r * cols + c)] + best;
      }
    int c = 0;
    for (int k = 1; k < cols; ++k)
      if (m[static_cast<size_t>((h - 1) * cols + k)] < m[static_cast<size_t>((h - 1) * cols + c)]) c = k;
    std::vector<int> path(static_cast<size_t>(h)), pixels(static_cast<size_t>(h));
    for (int r = h - 1; r >= 0; --r) {
      path[static_cast<size_t>(r)] = c;
      if (r == 0) break;
      const float* p = &m[static_cast<size_t>((r - 1) * cols)];
      int next = c;
      if (c > 0 && p[c - 1] < p[next]) next = c - 1;
      if (c + 1 < cols && p[c + 1] < p[next]) next = c + 1;
      c = next;
    }
    std::vector<float> e2;
    std::vector<int> i2;
    for (int r = 0; r < h; ++r)
      for (int k = 0; k < cols; ++k) {
        if (k == path[static_cast<size_t>(r)]) {
          pixels[static_cast<size_t>(r)] = idx[static_cast<size_t>(r * cols + k)];
          continue;
        }
        e2.push_back(e[static_cast<size_t>(r * cols + k)]);
        i2.push_back(idx[static_cast<size_t>(r * cols + k)]);
      }
    e.swap(e2), idx.swap(i2);
    out.push_back(pixels);
  }
  return out;
}

TEST(SeamCarving, IncrementalCumulativeEnergyGivesTheTextbookSeams) {
  // carveSeams updates the cumulative energy only in the cone below each removed seam: on images with
  // many ties and frozen pixels it must still remove exactly the seams of the full recomputation.
  std::mt19937 rng(5);
  for (int trial = 0; trial < 6; ++trial) {
    const int w = 50 + 7 * trial, h = 40 + 5 * trial;
    std::uniform_int_distribution<int> value(0, trial % 2 ? 3 : 255);
    std::bernoulli_distribution frozen(0.05);
    std::vector<float> e(static_cast<size_t>(w * h));
    for (float& v : e) v = frozen(rng) ? kInf : static_cast<float>(value(rng));
    const int seams = 30;
    const std::vector<std::vector<int>> want = referenceVerticalSeams(e, w, h, seams);
    const CarveResult r = carveSeams(e, w, h, seams, 0, SeamOrder::Blocks);
    ASSERT_EQ(r.seams.size(), want.size()) << "trial " << trial;
    for (size_t k = 0; k < want.size(); ++k)
      EXPECT_EQ(r.seams[k].pixels, want[k]) << "trial " << trial << " seam " << k;
    EXPECT_LT(r.cellsUpdated, static_cast<size_t>(seams) * static_cast<size_t>(w * h))
        << "the cone update recomputes less than the whole image";
  }
}

TEST(SeamCarving, ThreadsDoNotChangeTheResult) {
  // Large enough (over 2^20 pixels) for the rows to be moved in bands.
  const int w = 1100, h = 1000;
  std::mt19937 rng(9);
  std::uniform_int_distribution<int> value(0, 20);
  std::vector<float> e(static_cast<size_t>(w) * h);
  for (float& v : e) v = static_cast<float>(value(rng));
  const CarveResult one = carveSeams(e, w, h, 4, 3, SeamOrder::Interleaved, {}, nullptr, 1);
  const CarveResult two = carveSeams(e, w, h, 4, 3, SeamOrder::Interleaved, {}, nullptr, 2);
  EXPECT_EQ(one.finalCol, two.finalCol);
  EXPECT_EQ(one.finalRow, two.finalRow);
  EXPECT_EQ(one.mergedInto, two.mergedInto);
}

TEST(SeamCarving, AFrozenRowStopsVerticalSeamsAndSaysWhere) {
  const int w = 10, h = 8;
  std::vector<float> e(static_cast<size_t>(w * h), 1.0f);
  for (int c = 0; c < w; ++c) e[static_cast<size_t>(5 * w + c)] = kInf;
  const CarveResult r = carveSeams(e, w, h, 3, 2, SeamOrder::Blocks);
  EXPECT_EQ(r.verticalRemoved, 0);
  EXPECT_EQ(r.horizontalRemoved, 2);
  EXPECT_EQ(r.verticalBlockedAt / w, 5);
  EXPECT_EQ(r.horizontalBlockedAt, -2);
}

TEST(Energy, DistanceTransformIsExact) {
  std::mt19937 rng(11);
  std::bernoulli_distribution on(0.04);
  const int w = 23, h = 17;
  std::vector<char> f(static_cast<size_t>(w * h));
  for (char& v : f) v = on(rng) ? 1 : 0;
  f[5] = 1;
  const std::vector<double> d = squaredDistanceTransform(f, w, h);
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      double best = std::numeric_limits<double>::infinity();
      for (int r2 = 0; r2 < h; ++r2)
        for (int c2 = 0; c2 < w; ++c2)
          if (f[static_cast<size_t>(r2 * w + c2)])
            best = std::min(best, double((r - r2) * (r - r2) + (c - c2) * (c - c2)));
      EXPECT_DOUBLE_EQ(d[static_cast<size_t>(r * w + c)], best);
    }
}

TEST(Energy, HighNearTheSkeletonLowInEmptyAreasInfiniteWhenFrozen) {
  SkeletonRaster raster;
  raster.frame.width = 20;
  raster.frame.height = 5;
  raster.ink.assign(100, 0.0f);
  raster.freezeOwner.assign(100, kNotFrozen);
  for (int r = 0; r < 5; ++r) raster.ink[static_cast<size_t>(r * 20)] = 255.0f;  // a street along column 0
  raster.freezeOwner[0] = kFrozenStreetNode;
  const std::vector<float> e = seamEnergy(raster, 0.5);
  EXPECT_TRUE(std::isinf(e[0]));
  EXPECT_FLOAT_EQ(e[20], 255.0f);  // ink 255 and distance 0
  EXPECT_FLOAT_EQ(e[39], 0.0f);    // farthest pixel: no ink, inverted distance 0
  for (int c = 1; c < 19; ++c) EXPECT_GT(e[static_cast<size_t>(20 + c)], e[static_cast<size_t>(20 + c + 1)]);
  const std::vector<float> grayOnly = seamEnergy(raster, 1.0);
  EXPECT_FLOAT_EQ(grayOnly[25], 0.0f);
}

}  // namespace
}  // namespace urbanvec::shrink
