// Plain data shared by the stages of the cadastre pipeline (issue 17; spec pueyo-urban-data.md part A):
// the drawing as read (polylines tagged with their layer role, floor labels), the cleaned linework the
// stages pass on, a small spatial grid used by every proximity query, and the pipeline's options.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <unordered_map>
#include <vector>

#include "urbanvec/core/geometry.hpp"

namespace urbanvec::cadastre {

/// Layer roles as bits, so a segment drawn on several layers keeps all of them (§A.3, §A.7).
enum LayerBit : std::uint8_t { kBlockLayer = 1, kLotLayer = 2, kBuildingLayer = 4 };

/// One polyline of the drawing (§A.3: every entity of a selected layer becomes a polyline).
struct CadLine {
  LineString line;
  std::uint8_t layer = kBlockLayer;
};

/// One text entity of the number-of-floors layer.
struct CadLabel {
  Vec2 p;
  std::string text;
};

/// Cleaned linework: representative vertices and straight segments between them.
struct Segment {
  int a = -1;
  int b = -1;
  std::uint8_t layers = 0;
};
/// One drawn segment end as it was before collapsing: the vertex it became, the vertex at the other
/// end of its segment, and where it was drawn (the observations of the geometric adjustment).
struct EndCopy {
  int vertex = -1;
  int other = -1;
  Vec2 p;
};
struct Linework {
  std::vector<Vec2> vertices;
  std::vector<Segment> segments;
  /// Per vertex, when filled: 1 where lines already met exactly in the drawing (a sound vertex that
  /// segment cleaning leaves in place), 0 for a free end.
  std::vector<char> sound;
  /// Every drawn segment end (two per segment step that did not collapse to a point).
  std::vector<EndCopy> copies;
};

/// The options of the whole pipeline; every number of the thesis is a default here (§A.9).
struct CadastreOptions {
  /// §A.4/§A.5 Collapsing Threshold (m). The thesis used 1 m on Girona's drawings. Measured on the
  /// Spanish cadastre sample (20 % of edges < 1 m) with closest-first collapsing: the copies of a vertex
  /// drawn with 0.3 m of jitter each lie up to ~0.7 m apart, and every threshold from 0.7 to 0.8 m keeps
  /// blocks and parcels (recall >= 0.97) while merging fewer distinct vertices than 1 m (building-part
  /// recall at L2 0.74 against 0.69 with 1 m); clean drawings are exact at any value (free ends only).
  double collapsingThreshold = 0.75;
  static constexpr double thesisCollapsingThreshold = 1.0;
  /// §A.6.1 Block Threshold (m): "slightly smaller than the narrowest street". The narrowest street
  /// of the sample is 2.5 m wide, hence 2 m; the thesis's value is 3 m.
  double blockThreshold = 2.0;
  static constexpr double thesisBlockThreshold = 3.0;
  /// §A.4 anti-drift rule on failure: true reverts the collapse as the thesis does (the farthest
  /// original is split off); false (measured better: a reverted cluster leaves slivers) keeps the new
  /// vertex apart and the representative whole. Either way no cluster grows wider than the threshold.
  /// Applies to the drawing-order sweep only (closestFirst false): closest-first never reverts.
  bool thesisRevert = false;
  /// Beyond the thesis: collapse the closest pairs of coordinates first (agglomerative, independent
  /// of the drawing order) instead of the thesis's sweep in drawing order, which puts a copy in the
  /// first representative within reach even when a copy of its own vertex comes later.
  bool closestFirst = true;
  /// Beyond the thesis: only free ends (one segment at the coordinate) collapse; vertices where lines
  /// already meet exactly are kept apart, however close (20 % of the sample's edges are < 1 m).
  bool freeEndsOnly = true;
  /// Degree-2 vertices within this share of the Collapsing Threshold of the straight line through
  /// their chain neighbours are dropped (straightenChains); 0 keeps every vertex.
  double straightenShare = 0.0;
  /// Circuits whose mean width 2 area / perimeter is below this (m) are slivers between nearly
  /// coincident lines, dropped: two copies of a line drawn with up to ~0.35 m of error each leave
  /// slivers up to that wide (was 0.35 times the Collapsing Threshold, which left some as sub-blocks
  /// below 1 m and dropped thin real parts of clean drawings above it).
  double sliverWidth = 0.34;
  /// Beyond the thesis: on a drawing whose copies coincide (copyNoise under kCleanNoise), a building
  /// face thinner than `sliverWidth` that holds a number-of-floors label (one floor or more above
  /// ground) is a building part, not a sliver, and is kept: walls, passages and stair strips 0.2-0.3 m
  /// wide are drawn as parts in the cadastre (2 of the sample's 294, lost even on the clean drawing
  /// otherwise). On a noisy drawing a thin labelled face is a fragment of a part cut by jittered
  /// copies (L2, 5 seeds: 14 such faces, none a part at IoU 0.9) and is dropped as before.
  bool keepLabelledThin = true;
  /// Beyond the thesis: geometric adjustment once the topology is known (geometric_adjustment.hpp):
  /// each vertex is fitted to all the drawn copies of its segment ends (across each copy's segment at
  /// full weight, along it with a Huber weight), with soft constraints keeping vertices within
  /// `straightAngle` degrees of 180 on the line of their neighbours and angles within `rightAngle`
  /// degrees of 90 square (0 disables either). Measured on the sample's L2 drawings (5 seeds):
  /// building-part recall 0.785 against 0.744 with the mean of the copies (docs/cadastre.md).
  bool adjust = true;
  /// Beyond the thesis (vertex_merging.hpp): after collapsing and segment cleaning, two vertices closer
  /// than this many times the drawing's noise (copyNoise) merge when no drawn segment joins them, no
  /// face but a sliver collapses and no crossing is created: the jittered copies of one drawn vertex
  /// split over several vertices become one again. A clean drawing (noise under 1 mm) is left as it
  /// is; 0 disables.
  double mergeSplit = 3.0;
  /// Beyond the thesis (segment_cleaning.hpp): segment cleaning moves a vertex onto a segment within
  /// the Collapsing Threshold only when it is a stray end — a free end (one segment) in one of its
  /// layers, or on the block layer. A vertex of lot and building lines met by two or more segments in
  /// each layer is a corner or a through point and stays (a line passing near it is a neighbour: 20 % of
  /// the sample's edges are under 1 m). Measured on the L2 drawings (5 seeds): building-part recall
  /// 0.805 against 0.790 when every vertex may move (`snapJoined` true, the thesis's §A.5 reading);
  /// block-layer vertices keep moving because a block corner whose copies split needs it (blocks lost
  /// on 2 of 5 seeds otherwise).
  bool snapJoined = false;
  double straightAngle = 10.0;
  double rightAngle = 10.0;
  /// Faces smaller than this (m²) are slivers between nearly coincident lines and are dropped.
  double minFaceArea = 0.1;
  /// A label outside every building element goes to the nearest one within this distance (m).
  double labelSearchDistance = 1.5;
  /// §A.8 floor heights: h = groundFloor + upperFloor (floors - 1) + offset.
  double groundFloorHeight = 3.0;
  double upperFloorHeight = 2.5;
  /// Largest magnitude of the seeded uniform offset added to each height (thesis: "a small random
  /// offset"); 0 keeps heights exact.
  double heightOffset = 0.0;
  std::uint64_t seed = 0;
  /// Worker threads (0 = all cores): with two or more, the parcel and building graphs are built side
  /// by side. The output does not depend on it.
  int threads = 1;
};

/// Exact coordinates as a hash key (-0.0 and 0.0 are the same point).
inline std::pair<std::uint64_t, std::uint64_t> coordinateKey(const Vec2& p) {
  std::uint64_t x, y;
  const double px = p.x + 0.0, py = p.y + 0.0;
  std::memcpy(&x, &px, 8);
  std::memcpy(&y, &py, 8);
  return {x, y};
}
struct CoordinateHash {
  std::size_t operator()(const std::pair<std::uint64_t, std::uint64_t>& k) const {
    return std::hash<std::uint64_t>()(k.first * 0x9E3779B97F4A7C15ULL ^ k.second);
  }
};

/// Axis-aligned bounding box of points (empty: inverted infinite bounds, so nothing lies inside).
struct Box {
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  void add(const Vec2& p) {
    x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
  }
  bool contains(const Vec2& p) const { return p.x >= x0 && p.x <= x1 && p.y >= y0 && p.y <= y1; }
};
inline Box boxOf(const std::vector<Vec2>& points) {
  Box b;
  for (const Vec2& p : points) b.add(p);
  return b;
}

/// A uniform grid of ids by cell, for proximity queries (collapsing, snapping, clustering). Each cell's
/// ids are a list in insertion order, threaded through one pooled array (no allocation per cell).
class CellGrid {
 public:
  explicit CellGrid(double cell) : cell_(cell) {}
  double cell() const { return cell_; }
  std::int64_t key(std::int64_t cx, std::int64_t cy) const { return cx * 73856093LL ^ cy * 19349663LL; }
  std::int64_t cx(double x) const { return static_cast<std::int64_t>(std::floor(x / cell_)); }
  void insert(const Vec2& p, int id) { push(key(cx(p.x), cx(p.y)), id); }
  /// Removes one entry `id` from the cell of p (if there).
  void erase(const Vec2& p, int id) {
    auto it = cells_.find(key(cx(p.x), cx(p.y)));
    if (it == cells_.end()) return;
    Ends& e = it->second;
    for (int prev = -1, n = e.head; n >= 0; prev = n, n = nodes_[static_cast<size_t>(n)].next) {
      if (nodes_[static_cast<size_t>(n)].id != id) continue;
      const int next = nodes_[static_cast<size_t>(n)].next;
      (prev < 0 ? e.head : nodes_[static_cast<size_t>(prev)].next) = next;
      if (e.tail == n) e.tail = prev;
      return;
    }
  }
  /// Inserts `id` in every cell its box touches.
  void insertBox(double x0, double y0, double x1, double y1, int id) {
    for (std::int64_t i = cx(x0); i <= cx(x1); ++i)
      for (std::int64_t j = cx(y0); j <= cx(y1); ++j) push(key(i, j), id);
  }
  void insertBox(const Box& b, int id) { insertBox(b.x0, b.y0, b.x1, b.y1, id); }
  /// Calls f(ids) for every non-empty cell, in an order fixed by the cells' contents.
  template <class F>
  void forEachCell(F&& f) const {
    std::vector<std::pair<std::int64_t, int>> heads;
    heads.reserve(cells_.size());
    for (const auto& kv : cells_)
      if (kv.second.head >= 0) heads.emplace_back(kv.first, kv.second.head);
    std::sort(heads.begin(), heads.end());
    std::vector<int> ids;
    for (const auto& [k, head] : heads) {
      ids.clear();
      for (int n = head; n >= 0; n = nodes_[static_cast<size_t>(n)].next)
        ids.push_back(nodes_[static_cast<size_t>(n)].id);
      f(static_cast<const std::vector<int>&>(ids));
    }
  }
  /// Calls f(id) for the ids of every cell the box touches (an id may come more than once).
  template <class F>
  void query(double x0, double y0, double x1, double y1, F&& f) const {
    for (std::int64_t i = cx(x0); i <= cx(x1); ++i)
      for (std::int64_t j = cx(y0); j <= cx(y1); ++j) {
        auto it = cells_.find(key(i, j));
        if (it != cells_.end())
          for (int n = it->second.head; n >= 0; n = nodes_[static_cast<size_t>(n)].next)
            f(nodes_[static_cast<size_t>(n)].id);
      }
  }

 private:
  struct Node {
    int id;
    int next;
  };
  struct Ends {
    int head = -1;
    int tail = -1;
  };
  void push(std::int64_t k, int id) {
    Ends& e = cells_[k];
    const int n = static_cast<int>(nodes_.size());
    nodes_.push_back({id, -1});
    (e.tail < 0 ? e.head : nodes_[static_cast<size_t>(e.tail)].next) = n;
    e.tail = n;
  }
  double cell_;
  std::unordered_map<std::int64_t, Ends> cells_;
  std::vector<Node> nodes_;
};

}  // namespace urbanvec::cadastre
