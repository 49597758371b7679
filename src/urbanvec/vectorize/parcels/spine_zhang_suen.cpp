// Spec §3 D6 steps 1-3 (thesis §3.4.2, paper §3.3.2): rasterization, Zhang-Suen thinning and
// re-vectorization of the thinned pixels.
#include "urbanvec/vectorize/parcels/spine_zhang_suen.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "urbanvec/core/error.hpp"

namespace urbanvec::vectorize::parcels {

namespace {

int findRoot(std::vector<int>& parent, int a) {
  while (parent[a] != a) a = parent[a] = parent[parent[a]];
  return a;
}

}  // namespace

BinaryImage rasterizePolygon(const Polygon& polygon, int pixelsPerCell, int padding) {
  if (pixelsPerCell < 1) throw invalidOption("spine rasterization needs at least 1 pixel per cell");
  BinaryImage image;
  if (polygon.outer.size() < 4) return image;
  double minX = 1e300, minY = 1e300, maxX = -1e300, maxY = -1e300;
  for (const Vec2& p : polygon.outer) {
    minX = std::min(minX, p.x);
    minY = std::min(minY, p.y);
    maxX = std::max(maxX, p.x);
    maxY = std::max(maxY, p.y);
  }
  image.pixelSize = 1.0 / pixelsPerCell;
  image.origin = {minX - padding * image.pixelSize, minY - padding * image.pixelSize};
  image.width = static_cast<int>(std::ceil((maxX - minX) * pixelsPerCell)) + 2 * padding;
  image.height = static_cast<int>(std::ceil((maxY - minY) * pixelsPerCell)) + 2 * padding;
  image.pixels.assign(static_cast<size_t>(image.width) * image.height, 0);

  std::vector<const Ring*> rings{&polygon.outer};
  for (const Ring& h : polygon.holes) rings.push_back(&h);
  std::vector<double> crossings;
  for (int j = 0; j < image.height; ++j) {
    const double y = image.origin.y + (j + 0.5) * image.pixelSize;
    crossings.clear();
    for (const Ring* ring : rings) {
      for (size_t k = 0; k + 1 < ring->size(); ++k) {
        const Vec2& a = (*ring)[k];
        const Vec2& b = (*ring)[k + 1];
        if ((a.y <= y) != (b.y <= y)) crossings.push_back(a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y));
      }
    }
    std::sort(crossings.begin(), crossings.end());
    for (size_t k = 0; k + 1 < crossings.size(); k += 2) {
      const int from =
          std::max(0, static_cast<int>(std::ceil((crossings[k] - image.origin.x) / image.pixelSize - 0.5)));
      const int to =
          std::min(image.width - 1,
                   static_cast<int>(std::floor((crossings[k + 1] - image.origin.x) / image.pixelSize - 0.5)));
      for (int i = from; i <= to; ++i) image.pixels[static_cast<size_t>(j) * image.width + i] = 1;
    }
  }
  return image;
}

void zhangSuenThin(BinaryImage& image) {
  const int w = image.width, h = image.height;
  if (w == 0 || h == 0) return;
  // Neighbours P2..P9 clockwise from north (j grows northwards).
  static const int di[8] = {0, 1, 1, 1, 0, -1, -1, -1};
  static const int dj[8] = {1, 1, 0, -1, -1, -1, 0, 1};
  auto fg = [&](int i, int j) { return image.at(i, j); };

  // Only pixels with a background neighbour can be deleted (B(P) <= 6 needs one), so the scan is
  // limited to a candidate list that follows the shrinking border.
  std::vector<int> stamp(static_cast<size_t>(w) * h, -1);
  std::vector<int> candidates;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      if (!fg(i, j)) continue;
      for (int k = 0; k < 8; ++k)
        if (!fg(i + di[k], j + dj[k])) {
          candidates.push_back(j * w + i);
          break;
        }
    }
  int generation = 0;
  bool changed = true;
  std::vector<int> toDelete;
  while (changed) {
    changed = false;
    for (int sub = 0; sub < 2; ++sub) {
      toDelete.clear();
      for (int idx : candidates) {
        const int i = idx % w, j = idx / w;
        if (!fg(i, j)) continue;
        bool p[8];
        int b = 0;
        for (int k = 0; k < 8; ++k) {
          p[k] = fg(i + di[k], j + dj[k]);
          b += p[k];
        }
        if (b < 2 || b > 6) continue;
        int a = 0;
        for (int k = 0; k < 8; ++k) a += (!p[k] && p[(k + 1) % 8]);
        if (a != 1) continue;
        // p[0]=P2 (N), p[2]=P4 (E), p[4]=P6 (S), p[6]=P8 (W).
        if (sub == 0 ? (p[0] && p[2] && p[4]) || (p[2] && p[4] && p[6])
                     : (p[0] && p[2] && p[6]) || (p[0] && p[4] && p[6]))
          continue;
        toDelete.push_back(idx);
      }
      if (toDelete.empty()) continue;
      changed = true;
      for (int idx : toDelete) image.pixels[idx] = 0;
      ++generation;
      std::vector<int> next;
      auto add = [&](int idx) {
        if (image.pixels[idx] && stamp[idx] != generation) {
          stamp[idx] = generation;
          next.push_back(idx);
        }
      };
      for (int idx : candidates) add(idx);
      for (int idx : toDelete) {
        const int i = idx % w, j = idx / w;
        for (int k = 0; k < 8; ++k) {
          const int ni = i + di[k], nj = j + dj[k];
          if (ni >= 0 && nj >= 0 && ni < w && nj < h) add(nj * w + ni);
        }
      }
      candidates.swap(next);
    }
  }
}

SpineGraph pixelSpineGraph(const BinaryImage& image) {
  SpineGraph graph;
  const int w = image.width, h = image.height;
  std::vector<int> index(static_cast<size_t>(w) * h, -1);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
      if (image.at(i, j)) {
        index[static_cast<size_t>(j) * w + i] = static_cast<int>(graph.nodes.size());
        graph.nodes.push_back(image.centre(i, j));
      }
  auto id = [&](int i, int j) { return image.at(i, j) ? index[static_cast<size_t>(j) * w + i] : -1; };
  std::vector<int> degree(graph.nodes.size(), 0);
  auto addEdge = [&](int a, int b) {
    graph.edges.push_back({std::min(a, b), std::max(a, b)});
    ++degree[a];
    ++degree[b];
  };
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const int a = id(i, j);
      if (a < 0) continue;
      if (id(i + 1, j) >= 0) addEdge(a, id(i + 1, j));
      if (id(i, j + 1) >= 0) addEdge(a, id(i, j + 1));
    }
  static const int ddi[4] = {1, 1, -1, -1};
  static const int ddj[4] = {1, -1, 1, -1};
  const std::vector<int> fourDegree = degree;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const int a = id(i, j);
      if (a < 0 || fourDegree[a] > 1) continue;
      for (int k = 0; k < 4; ++k) {
        const int b = id(i + ddi[k], j + ddj[k]);
        if (b >= 0) addEdge(a, b);
      }
    }
  std::sort(graph.edges.begin(), graph.edges.end());
  graph.edges.erase(std::unique(graph.edges.begin(), graph.edges.end()), graph.edges.end());

  // A thinned 8-connected shape is one piece; join what the degree rule left apart.
  std::vector<int> parent(graph.nodes.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (const auto& e : graph.edges) parent[findRoot(parent, e[0])] = findRoot(parent, e[1]);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const int a = id(i, j);
      if (a < 0) continue;
      for (int k = 0; k < 2; ++k) {
        const int b = id(i + ddi[k], j + ddj[k]);
        if (b < 0) continue;
        const int ra = findRoot(parent, a), rb = findRoot(parent, b);
        if (ra == rb) continue;
        parent[ra] = rb;
        graph.edges.push_back({std::min(a, b), std::max(a, b)});
      }
    }
  return graph;
}

SpineGraph zhangSuenSpineGraph(const Polygon& polygon, int pixelsPerCell) {
  BinaryImage image = rasterizePolygon(polygon, pixelsPerCell);
  zhangSuenThin(image);
  return pixelSpineGraph(image);
}

}  // namespace urbanvec::vectorize::parcels
