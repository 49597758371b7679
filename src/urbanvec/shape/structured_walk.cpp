// Structured walk, spec wijgerse-boundary.md §6.2-§6.3 and §6.6 (thesis Eqs. 4.3-4.8, §5.3.2).
#include "urbanvec/shape/structured_walk.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "urbanvec/core/error.hpp"

namespace urbanvec::shape {

namespace {

// Two walks advance side by side in the two lanes of one register (GCC/Clang vector extensions: SSE2
// on x86-64, NEON on AArch64, plain scalar code elsewhere). Every lane operation is the same IEEE
// operation as the scalar formula, so the results are bit for bit those of walking one at a time.
using Lanes = double __attribute__((vector_size(16)));
using LaneMask = std::int64_t __attribute__((vector_size(16)));  // comparison result: all bits or none

Lanes loadLanes(const double* p) {
  Lanes v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

/// mask ? a : b, lane by lane.
Lanes select(LaneMask mask, Lanes a, Lanes b) {
  return reinterpret_cast<Lanes>((reinterpret_cast<LaneMask>(a) & mask) |
                                 (reinterpret_cast<LaneMask>(b) & ~mask));
}

/// Bit k set when lane k of the mask is set.
unsigned laneBits(LaneMask mask) {
#if defined(__SSE2__)
  return static_cast<unsigned>(_mm_movemask_pd(reinterpret_cast<__m128d>(mask)));
#else
  return static_cast<unsigned>(mask[0] & 1) | static_cast<unsigned>(mask[1] & 2);
#endif
}

/// Correctly rounded square root per lane (IEEE, as std::sqrt).
Lanes sqrtLanes(Lanes v) {
#if defined(__SSE2__)
  return reinterpret_cast<Lanes>(_mm_sqrt_pd(reinterpret_cast<__m128d>(v)));
#else
  return Lanes{std::sqrt(v[0]), std::sqrt(v[1])};
#endif
}

/// What the root of a chord needs of its segment, in one cache line's reach.
struct Segment {
  double x, y;                  ///< start vertex
  double dx, dy;                ///< end - start
  double squaredLength;         ///< dx^2 + dy^2
  double inverseSquaredLength;  ///< 1 / squaredLength, to keep divisions out of the walk
};

/// The ring unrolled twice as plain coordinate arrays, so a walk from any vertex is a forward scan
/// without modulo, padded so that a block of vertices can be read past the end; and the per-segment
/// constants of the chord root.
class UnrolledRing {
 public:
  /// Vertices readable past the last one a walk may test (a probe reads up to kProbe at once).
  static constexpr size_t kProbe = 16;

  explicit UnrolledRing(const std::vector<Vec2>& vertices) : size_(vertices.size()) {
    const size_t points = 2 * size_ + 1;
    x_.resize(points + kProbe);
    y_.resize(points + kProbe);
    for (size_t i = 0; i < x_.size(); ++i) {
      x_[i] = vertices[i % size_].x;
      y_[i] = vertices[i % size_].y;
    }
    segments_.resize(points - 1);
    for (size_t i = 0; i + 1 < points; ++i) {
      Segment& s = segments_[i];
      s.x = x_[i];
      s.y = y_[i];
      s.dx = x_[i + 1] - x_[i];
      s.dy = y_[i + 1] - y_[i];
      s.squaredLength = s.dx * s.dx + s.dy * s.dy;
      s.inverseSquaredLength = 1.0 / s.squaredLength;
    }
    for (size_t i = 0; i < size_; ++i) perimeter_ += distance(vertices[i], vertices[(i + 1) % size_]);
  }
  size_t size() const { return size_; }
  double x(size_t i) const { return x_[i]; }
  double y(size_t i) const { return y_[i]; }
  /// Segment i runs from vertex i to vertex i + 1.
  const Segment& segment(size_t i) const { return segments_[i]; }
  double perimeter() const { return perimeter_; }
  /// First vertex in [first, last] whose squared distance (x - cx)^2 + (y - cy)^2 is at least r2, or
  /// last + 1: the vertices tested in turn, as the walk is defined. Tests Block (4, 8 or 16) vertices
  /// at once without branching, reading past `last` into the padding and ignoring what it finds there:
  /// a chord mostly leaves within its first block, so the one branch per chord is well predicted.
  template <size_t Block>
  size_t firstOutside(size_t first, size_t last, double cx, double cy, double r2) const {
    for (size_t v = first; v <= last; v += Block) {
      unsigned outside = probe<Block>(v, cx, cy, r2);
      if (last + 1 - v < Block) outside &= (1u << (last + 1 - v)) - 1;
      if (outside != 0) return v + static_cast<size_t>(__builtin_ctz(outside));
    }
    return last + 1;
  }

 private:
  /// Bit k set when vertex first + k is outside (squared distance >= r2), for k < Size.
  template <size_t Size>
  unsigned probe(size_t first, double cx, double cy, double r2) const {
    const Lanes centreX{cx, cx};
    const Lanes centreY{cy, cy};
    const Lanes radius2{r2, r2};
    unsigned outside = 0;
    for (size_t k = 0; k < Size; k += 2) {
      const Lanes ex = loadLanes(&x_[first + k]) - centreX;
      const Lanes ey = loadLanes(&y_[first + k]) - centreY;
      outside |= laneBits(ex * ex + ey * ey >= radius2) << k;
    }
    return outside;
  }

  size_t size_;
  double perimeter_ = 0.0;
  std::vector<double> x_, y_;
  std::vector<Segment> segments_;
};

/// Outcome of one walk.
struct WalkCount {
  long fullChords = 0;
  double leftover = 0.0;
};

/// All walks of one chord length. Six walks run at once, in three lane pairs, so the CPU overlaps
/// their long dependency chains (circle test, root, next centre; with two pairs it waits on them, four
/// no longer fit its instruction window) and each root serves two walks. Their state stays in
/// registers while none of them ends; a walk that ends is replaced by the next start vertex, or, when
/// none is left, by a copy of a running walk that is not recorded.
class ScaleWalker {
 public:
  ScaleWalker(const UnrolledRing& ring, size_t skip, double chord, size_t block)
      : ring_(ring),
        skip_(skip),
        chord_(chord),
        chord2_(chord * chord),
        block_(block),
        // Each full chord advances at least `chord` along the ring; more means rounding stalled a walk.
        chordLimit_(static_cast<long>(ring.perimeter() / chord) + 2) {}

  /// fullChords and leftover of the walks from vertices 0, skip, 2 skip, ... in that order.
  std::vector<WalkCount> run() {
    results_.assign((ring_.size() + skip_ - 1) / skip_, WalkCount{});
    for (size_t lane = 0; lane < kLanes; ++lane) load(lane);
    while (std::any_of(lanes_, lanes_ + kLanes, [](const WalkState& w) { return w.live; })) {
      size_t exit[kLanes];
      switch (block_) {
        case 4:
          walkUntilOneEnds<4>(exit);
          break;
        case 8:
          walkUntilOneEnds<8>(exit);
          break;
        default:
          walkUntilOneEnds<16>(exit);
          break;
      }
      for (size_t lane = 0; lane < kLanes; ++lane) {
        WalkState& w = lanes_[lane];
        if (exit[lane] <= w.end) continue;
        if (w.live) {
          const size_t start = w.end - ring_.size();
          results_[w.walk] = {w.fullChords, std::hypot(ring_.x(start) - w.cx, ring_.y(start) - w.cy)};
        }
        w.live = false;
        w.ended = true;
      }
      for (size_t lane = 0; lane < kLanes; ++lane)
        if (lanes_[lane].ended) load(lane);
    }
    return std::move(results_);
  }

 private:
  static constexpr size_t kPairs = 3;
  static constexpr size_t kLanes = 2 * kPairs;

  struct WalkState {
    double cx = 0.0, cy = 0.0;  ///< current point
    double t = 0.0;             ///< its parameter on segment `segment`
    size_t segment = 0;
    size_t end = 0;  ///< start + vertices: the walk ends back at its start vertex
    size_t walk = 0;
    long fullChords = 0;
    bool live = false;   ///< recorded; a lane that is not live repeats another lane's walk
    bool ended = false;  ///< needs a new walk
  };

  /// Puts the next walk into `lane`; without one, a copy of a running walk (or nothing).
  void load(size_t lane) {
    WalkState& w = lanes_[lane];
    w.ended = false;
    if (next_ < results_.size()) {
      const size_t start = next_ * skip_;
      w = WalkState{ring_.x(start), ring_.y(start), 0.0, start, start + ring_.size(), next_++, 0,
                    true,           false};
      return;
    }
    for (const WalkState& other : lanes_)
      if (other.live) {
        w = other;
        w.live = false;
        return;
      }
    w.live = false;
  }

  /// Advances all walks chord by chord until at least one has no full chord left; `exit` gets each
  /// lane's next exit vertex (beyond `end` for those that ended).
  template <size_t Block>
  void walkUntilOneEnds(size_t exit[kLanes]) {
    Lanes cx[kPairs], cy[kPairs], t[kPairs];
    size_t segment[kLanes], end[kLanes];
    long mostChords = 0;
    for (size_t p = 0; p < kPairs; ++p) {
      const WalkState& a = lanes_[2 * p];
      const WalkState& b = lanes_[2 * p + 1];
      cx[p] = Lanes{a.cx, b.cx};
      cy[p] = Lanes{a.cy, b.cy};
      t[p] = Lanes{a.t, b.t};
    }
    for (size_t lane = 0; lane < kLanes; ++lane) {
      segment[lane] = lanes_[lane].segment;
      end[lane] = lanes_[lane].end;
      mostChords = std::max(mostChords, lanes_[lane].fullChords);
    }
    long steps = 0;
    while (true) {
      bool ended = false;
      // Unrolled, so that the lanes' state lives in registers and the circle tests interleave (8 %
      // faster than the loops, and a quarter of the mispredicted branches).
#pragma GCC unroll 8
      for (size_t lane = 0; lane < kLanes; ++lane) {
        exit[lane] = ring_.firstOutside<Block>(segment[lane] + 1, end[lane], cx[lane / 2][lane % 2],
                                               cy[lane / 2][lane % 2], chord2_);
        ended |= exit[lane] > end[lane];
      }
      if (ended) break;
#pragma GCC unroll 4
      for (size_t p = 0; p < kPairs; ++p)
        advance(cx[p], cy[p], t[p], segment[2 * p], segment[2 * p + 1], exit[2 * p] - 1, exit[2 * p + 1] - 1);
      if (mostChords + ++steps > chordLimit_)
        throw invalidOption("the chord length " + std::to_string(chord_) +
                            " is too short for the precision of the coordinates");
    }
    for (size_t lane = 0; lane < kLanes; ++lane) {
      WalkState& w = lanes_[lane];
      w.cx = cx[lane / 2][lane % 2];
      w.cy = cy[lane / 2][lane % 2];
      w.t = t[lane / 2][lane % 2];
      w.segment = segment[lane];
      w.fullChords += steps;
    }
  }

  /// One chord for two walks: the new point is the larger root of |a + t d - centre| = chord on the
  /// exit segments e0 and e1, never behind the current point when that is on the same segment.
  void advance(Lanes& cx, Lanes& cy, Lanes& t, size_t& s0, size_t& s1, size_t e0, size_t e1) const {
    const Segment& g0 = ring_.segment(e0);
    const Segment& g1 = ring_.segment(e1);
    const Lanes ax{g0.x, g1.x};
    const Lanes ay{g0.y, g1.y};
    const Lanes dx{g0.dx, g1.dx};
    const Lanes dy{g0.dy, g1.dy};
    const Lanes dd{g0.squaredLength, g1.squaredLength};
    const Lanes inverse{g0.inverseSquaredLength, g1.inverseSquaredLength};
    const LaneMask sameSegment{e0 == s0 ? -1 : 0, e1 == s1 ? -1 : 0};
    const Lanes zero{0.0, 0.0};
    const Lanes one{1.0, 1.0};
    const Lanes low = select(sameSegment, t, zero);
    const Lanes fx = ax - cx;
    const Lanes fy = ay - cy;
    const Lanes fd = fx * dx + fy * dy;
    Lanes disc = fd * fd - dd * ((fx * fx + fy * fy) - Lanes{chord2_, chord2_});
    disc = select(zero < disc, disc, zero);  // std::max(0.0, disc)
    const Lanes root = (-fd + sqrtLanes(disc)) * inverse;
    t = select(root < low, low, select(one < root, one, root));  // std::clamp(root, low, 1.0)
    cx = ax + dx * t;
    cy = ay + dy * t;
    s0 = e0;
    s1 = e1;
  }

  const UnrolledRing& ring_;
  size_t skip_;
  double chord_;
  double chord2_;
  size_t block_;
  long chordLimit_;
  size_t next_ = 0;
  WalkState lanes_[kLanes];
  std::vector<WalkCount> results_;
};

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
    // Vertices tested per block: on the recommended-range hulls, chords up to 1.5 l0 leave within 4
    // vertices 93-99 % of the time, chords up to 3 l0 within 8 92-99 %; longer chords take 16.
    const double ratio = scale.chord / result.baseChord;
    const size_t block = ratio < 1.9 ? 4 : ratio < 3.5 ? 8 : 16;
    // The thesis starts at x = 1 (mod s) with 1-based vertices: the first, then every s-th.
    const std::vector<WalkCount> walks = ScaleWalker(unrolled, skip, scale.chord, block).run();
    double countSum = 0.0;
    double meanSum = 0.0;
    double fullSum = 0.0;
    for (const WalkCount& walk : walks) {
      const double chords =
          static_cast<double>(walk.fullChords) + 1.0;  // the leftover chord counts (Eq. 4.3)
      countSum += chords;
      meanSum += (walk.fullChords * scale.chord + walk.leftover) / chords;  // Eq. 4.4
      fullSum += static_cast<double>(walk.fullChords);
    }
    // With skipping, the averages run over the walked starts only (spec §6.6 [INF]).
    scale.chordCount = countSum / walks.size();
    scale.meanChord = meanSum / walks.size();
    scale.fullChords = fullSum / walks.size();
    result.startVertices = walks.size();
    result.scales.push_back(scale);
  }
  return result;
}

}  // namespace urbanvec::shape
