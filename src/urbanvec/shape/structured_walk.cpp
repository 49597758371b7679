// Structured walk, spec wijgerse-boundary.md §6.2-§6.3 and §6.6 (thesis Eqs. 4.3-4.8, §5.3.2).
#include "urbanvec/shape/structured_walk.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "urbanvec/core/error.hpp"

namespace urbanvec::shape {

namespace {

double squaredDistance(const Vec2& a, const Vec2& b) {
  const double dx = a.x - b.x;
  const double dy = a.y - b.y;
  return dx * dx + dy * dy;
}

/// The ring unrolled twice, with cumulative arc length, so a walk from any vertex is a forward scan
/// over plain arrays (no modulo in the inner loop).
class UnrolledRing {
 public:
  explicit UnrolledRing(const std::vector<Vec2>& vertices) : size_(vertices.size()) {
    points_.reserve(2 * size_ + 1);
    for (size_t i = 0; i <= 2 * size_; ++i) points_.push_back(vertices[i % size_]);
    arc_.resize(2 * size_ + 1, 0.0);
    inverseSquaredLength_.resize(2 * size_, 0.0);
    for (size_t i = 0; i < 2 * size_; ++i) {
      arc_[i + 1] = arc_[i] + distance(points_[i], points_[i + 1]);
      inverseSquaredLength_[i] = 1.0 / squaredDistance(points_[i], points_[i + 1]);
    }
  }
  size_t size() const { return size_; }
  const Vec2& at(size_t i) const { return points_[i]; }
  double arc(size_t i) const { return arc_[i]; }
  /// 1 / |segment i|^2, precomputed to keep divisions out of the walk.
  double inverseSquaredLength(size_t i) const { return inverseSquaredLength_[i]; }
  double perimeter() const { return arc_[size_]; }
  /// First index in (from, to] whose arc length reaches `target`, or to + 1 when none does. Galloping
  /// from `from`: the answer is usually a few vertices ahead.
  size_t firstReaching(size_t from, size_t to, double target) const {
    size_t lo = from;  // arc_[lo] < target
    size_t step = 1;
    size_t hi = from + 1;
    while (hi <= to && arc_[hi] < target) {
      lo = hi;
      step *= 2;
      hi = from + step;
    }
    if (hi > to) {
      if (arc_[to] < target) return to + 1;
      hi = to;
    }
    // arc_[lo] < target <= arc_[hi]
    return static_cast<size_t>(std::lower_bound(arc_.begin() + static_cast<std::ptrdiff_t>(lo + 1),
                                                arc_.begin() + static_cast<std::ptrdiff_t>(hi), target) -
                               arc_.begin());
  }

 private:
  size_t size_;
  std::vector<Vec2> points_;
  std::vector<double> arc_;
  std::vector<double> inverseSquaredLength_;
};

/// One walk in progress: the current point lies on segment (segment, segment + 1) at parameter t.
struct Walk {
  size_t start = 0;
  size_t end = 0;  ///< start + vertices: the walk ends back at its start vertex
  size_t segment = 0;
  double t = 0.0;
  Vec2 centre;
  long fullChords = 0;
  double leftover = 0.0;
  bool done = false;
  /// Each full chord advances at least `chord` along the ring; more means rounding stalled the walk.
  long chordLimit = 0;
};

Walk startWalk(const UnrolledRing& ring, size_t start, double chord) {
  Walk walk;
  walk.chordLimit = static_cast<long>(ring.perimeter() / chord) + 2;
  walk.start = start;
  walk.end = start + ring.size();
  walk.segment = start;
  walk.centre = ring.at(start);
  return walk;
}

/// Advances a walk by one chord of length `chord`, or finishes it with its leftover chord when the
/// rest of the ring stays inside the circle.
void advance(const UnrolledRing& ring, Walk& walk, double chord, double chord2) {
  while (true) {
    const Vec2& a = ring.at(walk.segment);
    const Vec2& b = ring.at(walk.segment + 1);
    if (squaredDistance(b, walk.centre) >= chord2) {
      // The ring leaves the circle on this segment: the larger root of |a + t d - centre| = chord.
      const Vec2 d = b - a;
      const Vec2 f = a - walk.centre;
      const double dd = dot(d, d);
      const double fd = dot(f, d);
      const double disc = std::max(0.0, fd * fd - dd * (dot(f, f) - chord2));
      const double root =
          std::clamp((-fd + std::sqrt(disc)) * ring.inverseSquaredLength(walk.segment), walk.t, 1.0);
      walk.centre = a + d * root;
      walk.t = root;
      ++walk.fullChords;
      if (walk.fullChords > walk.chordLimit)
        throw invalidOption("the chord length " + std::to_string(chord) +
                            " is too short for the precision of the coordinates");
      return;
    }
    // b is inside the circle. Short chords leave it within a few segments: test those first.
    size_t vertex = walk.segment + 1;
    const size_t scanEnd = std::min(walk.end, vertex + 4);
    while (vertex < scanEnd && squaredDistance(ring.at(vertex + 1), walk.centre) < chord2) ++vertex;
    walk.t = 0.0;
    if (vertex < scanEnd) {
      walk.segment = vertex;
      continue;
    }
    // Every point within arc length (chord - |v - centre|) of vertex v is inside too, so jump to the
    // first vertex beyond that distance instead of testing each segment.
    double inside = std::sqrt(squaredDistance(ring.at(vertex), walk.centre));
    bool crossed = false;
    while (vertex < walk.end) {
      const size_t next = ring.firstReaching(vertex, walk.end, ring.arc(vertex) + (chord - inside));
      if (next > walk.end) break;  // the rest of the ring stays inside
      const double reach2 = squaredDistance(ring.at(next), walk.centre);
      if (reach2 >= chord2) {
        walk.segment = next - 1;
        crossed = true;
        break;
      }
      vertex = next;
      inside = std::sqrt(reach2);
    }
    if (!crossed) {
      walk.leftover = distance(ring.at(walk.start), walk.centre);
      walk.done = true;
      return;
    }
  }
}

}  // namespace

StructuredWalk structuredWalk(const Ring& ring, const StructuredWalkOptions& options) {
  if (options.scales < 2) throw invalidOption("the structured walk needs at least 2 chord lengths (-scales)");
  if (options.skip < 1) throw invalidOption("the start-vertex skip (-skip) must be at least 1");
  if (!(options.scaleFactor > 1.0))
    throw invalidOption("the chord scale factor (-k) must be greater than 1, got " +
                        std::to_string(options.scaleFactor));
  if (!(options.baseChord >= 0.0) || !std::isfinite(options.baseChord))
    throw invalidOption("the base chord length must be positive (0 = mean segment length)");
  std::vector<Vec2> vertices;
  vertices.reserve(ring.size());
  for (const Vec2& p : ring)
    if (vertices.empty() || p != vertices.back()) vertices.push_back(p);
  while (vertices.size() > 1 && vertices.back() == vertices.front()) vertices.pop_back();
  if (vertices.size() < 3)
    throw invalidInput("a ring needs at least 3 distinct vertices for a structured walk");

  const UnrolledRing unrolled(vertices);
  StructuredWalk result;
  result.vertices = unrolled.size();
  result.baseChord = options.baseChord > 0.0 ? options.baseChord : unrolled.perimeter() / unrolled.size();
  const size_t skip = static_cast<size_t>(options.skip);
  for (int n = 0; n < options.scales; ++n) {
    WalkScale scale;
    scale.chord = result.baseChord * std::pow(options.scaleFactor, n);
    const double chord2 = scale.chord * scale.chord;
    double countSum = 0.0;
    double meanSum = 0.0;
    double fullSum = 0.0;
    size_t starts = 0;
    // The thesis starts at x = 1 (mod s) with 1-based vertices: the first, then every s-th. Walks
    // advance in groups, one chord each in turn, so the CPU overlaps their long dependency chains.
    constexpr size_t kGroup = 4;
    for (size_t first = 0; first < unrolled.size(); first += kGroup * skip) {
      Walk walks[kGroup];
      size_t count = 0;
      for (size_t x = first; x < unrolled.size() && count < kGroup; x += skip)
        walks[count++] = startWalk(unrolled, x, scale.chord);
      for (size_t active = count; active > 0;) {
        active = 0;
        for (size_t w = 0; w < count; ++w)
          if (!walks[w].done) {
            advance(unrolled, walks[w], scale.chord, chord2);
            active += walks[w].done ? 0 : 1;
          }
      }
      for (size_t w = 0; w < count; ++w, ++starts) {
        const Walk& walk = walks[w];
        const double chords =
            static_cast<double>(walk.fullChords) + 1.0;  // the leftover chord counts (Eq. 4.3)
        countSum += chords;
        meanSum += (walk.fullChords * scale.chord + walk.leftover) / chords;  // Eq. 4.4
        fullSum += static_cast<double>(walk.fullChords);
      }
    }
    // With skipping, the averages run over the walked starts only (spec §6.6 [INF]).
    scale.chordCount = countSum / starts;
    scale.meanChord = meanSum / starts;
    scale.fullChords = fullSum / starts;
    result.startVertices = starts;
    result.scales.push_back(scale);
  }
  return result;
}

}  // namespace urbanvec::shape
