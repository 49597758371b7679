// Segment cleaning (spec pueyo-urban-data.md §A.5). See segment_cleaning.hpp.
#include "urbanvec/cadastre/segment_cleaning.hpp"

#include <algorithm>
#include <array>

namespace urbanvec::cadastre {

std::size_t dropDuplicateSegments(std::vector<Segment>& segments) {
  for (Segment& s : segments)
    if (s.a > s.b) std::swap(s.a, s.b);
  std::sort(segments.begin(), segments.end(),
            [](const Segment& x, const Segment& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; });
  std::vector<Segment> out;
  out.reserve(segments.size());
  for (const Segment& s : segments) {
    if (!out.empty() && out.back().a == s.a && out.back().b == s.b) {
      out.back().layers |= s.layers;
      continue;
    }
    out.push_back(s);
  }
  const std::size_t dropped = segments.size() - out.size();
  segments.swap(out);
  return dropped;
}

void cleanSegments(Linework& lw, double threshold, SegmentCleaningStats& stats, const Progress& progress,
                   bool snapJoined) {
  stats = {};
  stats.duplicateSegments += dropDuplicateSegments(lw.segments);
  // Neighbours of each vertex (sorted), to leave a vertex joined to a segment's end alone (a notch).
  std::vector<std::vector<int>> adjacent(lw.vertices.size());
  for (const Segment& s : lw.segments) {
    adjacent[static_cast<size_t>(s.a)].push_back(s.b);
    adjacent[static_cast<size_t>(s.b)].push_back(s.a);
  }
  for (auto& a : adjacent) std::sort(a.begin(), a.end());
  auto joined = [&](int v, int w) {
    const auto& a = adjacent[static_cast<size_t>(v)];
    return std::binary_search(a.begin(), a.end(), w);
  };
  // Vertices of lot and building lines where every layer's lines already meet (two or more segments
  // per layer, none on the block layer): corners and through points whose copies found each other.
  // They stay where they are (unless `snapJoined`): a vertex near a line it is not on is a real short
  // edge or notch of the cadastre, and moving it onto the line folds that edge away.
  std::vector<char> keepOff(lw.vertices.size(), 0);
  if (!snapJoined) {
    std::vector<std::array<int, 3>> degree(lw.vertices.size(), {0, 0, 0});
    for (const Segment& s : lw.segments)
      for (int k = 0; k < 3; ++k)
        if (s.layers & (1 << k)) ++degree[static_cast<size_t>(s.a)][k], ++degree[static_cast<size_t>(s.b)][k];
    static_assert(kBlockLayer == 1 && kLotLayer == 2 && kBuildingLayer == 4, "layer bits");
    for (size_t v = 0; v < degree.size(); ++v) {
      const auto& d = degree[v];
      keepOff[v] = d[0] == 0 && d[1] != 1 && d[2] != 1 && d[1] + d[2] > 0;
    }
  }
  // Cells of about a typical segment (at least twice the threshold): each segment touches few cells.
  std::vector<double> lengths;
  for (const Segment& s : lw.segments)
    lengths.push_back(distance(lw.vertices[static_cast<size_t>(s.a)], lw.vertices[static_cast<size_t>(s.b)]));
  double cell = std::max(threshold, 1e-9) * 2.0;
  if (!lengths.empty()) {
    std::nth_element(lengths.begin(), lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2),
                     lengths.end());
    cell = std::max(cell, lengths[lengths.size() / 2]);
  }
  CellGrid grid(cell);
  for (size_t i = 0; i < lw.segments.size(); ++i) {
    const Vec2 a = lw.vertices[static_cast<size_t>(lw.segments[i].a)],
               b = lw.vertices[static_cast<size_t>(lw.segments[i].b)];
    grid.insertBox(std::min(a.x, b.x), std::min(a.y, b.y), std::max(a.x, b.x), std::max(a.y, b.y),
                   static_cast<int>(i));
  }
  // Split points per segment: (parameter along it, vertex).
  std::vector<std::vector<std::pair<double, int>>> splits(lw.segments.size());
  ProgressTicker ticker(progress, "cleaning segments", lw.vertices.size());
  std::vector<int> seen;
  for (size_t v = 0; v < lw.vertices.size(); ++v) {
    ticker.tick();
    if (!lw.sound.empty() && lw.sound[v]) continue;  // lines met here exactly: not a stray end
    const Vec2 p = lw.vertices[v];
    seen.clear();
    grid.query(p.x - threshold, p.y - threshold, p.x + threshold, p.y + threshold,
               [&](int s) { seen.push_back(s); });
    std::sort(seen.begin(), seen.end());
    seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
    // The nearest segment the vertex lies on (within the threshold, inside its span); the vertex
    // moves onto it (the stored segment keeps its geometry, §A.5) and splits it there.
    int best = -1;
    double bestD = threshold, bestT = 0.0;
    for (int si : seen) {
      const Segment& s = lw.segments[static_cast<size_t>(si)];
      const int iv = static_cast<int>(v);
      if (s.a == iv || s.b == iv || joined(iv, s.a) || joined(iv, s.b)) continue;
      const Vec2 a = lw.vertices[static_cast<size_t>(s.a)], b = lw.vertices[static_cast<size_t>(s.b)];
      const Vec2 ab = b - a;
      const double len2 = dot(ab, ab);
      if (len2 <= 0) continue;
      const double t = dot(p - a, ab) / len2;
      if (t <= 0.0 || t >= 1.0) continue;
      const double d = distance(p, a + ab * t);
      if (d < bestD) bestD = d, best = si, bestT = t;
    }
    if (best >= 0 && keepOff[v]) {
      ++stats.cornersKeptOff;
      continue;
    }
    if (best >= 0) {
      const Segment& s = lw.segments[static_cast<size_t>(best)];
      const Vec2 a = lw.vertices[static_cast<size_t>(s.a)], b = lw.vertices[static_cast<size_t>(s.b)];
      lw.vertices[v] = a + (b - a) * bestT;
      splits[static_cast<size_t>(best)].emplace_back(bestT, static_cast<int>(v));
    }
  }
  ticker.finish();
  std::vector<Segment> out;
  out.reserve(lw.segments.size());
  for (size_t i = 0; i < lw.segments.size(); ++i) {
    const Segment& s = lw.segments[i];
    auto& sp = splits[i];
    if (sp.empty()) {
      out.push_back(s);
      continue;
    }
    ++stats.verticesOnSegments;
    std::sort(sp.begin(), sp.end());
    int prev = s.a;
    for (const auto& [t, v] : sp) {
      if (v != prev) out.push_back({prev, v, s.layers});
      prev = v;
    }
    if (prev != s.b) out.push_back({prev, s.b, s.layers});
  }
  lw.segments.swap(out);
  stats.duplicateSegments += dropDuplicateSegments(lw.segments);
}

}  // namespace urbanvec::cadastre
