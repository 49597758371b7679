// Hyperstreamline tracing (spec chen-streets.md §8.2 RK integration with sign alignment, §8.3
// stopping criteria and look-ahead, §9.1 interleaving, §9.3 consolidated seeding with priority
// ω = e^(−d_b/λ), §11 density-modulated d_sep, §12 minor roads ending on major roads).
#include "urbanvec/streets/hyperstreamlines.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <set>
#include <utility>

#include "urbanvec/core/error.hpp"
#include "urbanvec/core/random.hpp"
#include "urbanvec/core/uniform_grid.hpp"
#include "urbanvec/streets/polygon_index.hpp"

namespace urbanvec::streets {
namespace {

/// Points of finished lines, for the d_sep / d_test distance queries.
class PointGrid {
 public:
  void init(const Vec2& lo, const Vec2& hi, double cell) { grid_.init(lo, hi, cell); }
  void add(const Vec2& p) { grid_.insert(p, p); }
  /// True when some point lies closer than r to p.
  bool anyWithin(const Vec2& p, double r) const {
    const double r2 = r * r;
    bool found = false;
    grid_.forBox(p - Vec2{r, r}, p + Vec2{r, r}, [&](const std::vector<Vec2>& c) {
      for (std::size_t k = 0; !found && k < c.size(); ++k) {
        const Vec2 d = c[k] - p;
        found = dot(d, d) < r2;
      }
    });
    return found;
  }

 private:
  UniformGrid<Vec2> grid_;  // §9.4 spatial acceleration
};

/// Segments of finished lines, for crossings (look-ahead joins, minor roads ending on major).
class SegmentGrid {
 public:
  void init(const Vec2& lo, const Vec2& hi, double cell) { grid_.init(lo, hi, cell); }
  void add(const Vec2& a, const Vec2& b) {
    const int id = static_cast<int>(segs_.size());
    segs_.push_back({a, b});
    grid_.insert(a, b, id);
  }
  /// The first crossing of p→q with a stored segment at a fraction t > minT, or t > 1 when none.
  double firstCrossing(const Vec2& p, const Vec2& q, double minT = 0.0) const {
    double best = 2.0;
    const Vec2 d = q - p;
    grid_.forBox(p, q, [&](const std::vector<int>& c) {
      for (int id : c) {
        const auto& [a, b] = segs_[static_cast<std::size_t>(id)];
        const Vec2 f = b - a;
        const double den = cross(d, f);
        if (den == 0.0) continue;
        const double t = cross(a - p, f) / den, u = cross(a - p, d) / den;
        if (t > minT && t <= 1.0 && u >= 0.0 && u <= 1.0) best = std::min(best, t);
      }
    });
    return best;
  }

 private:
  UniformGrid<int> grid_;
  std::vector<std::pair<Vec2, Vec2>> segs_;
};

enum class Stop { Boundary, Degenerate, Loop, Length, Close, Junction };

struct Half {
  LineString points;
  Stop stop = Stop::Boundary;
};

class Tracer {
 public:
  Tracer(const TensorField& field, const TraceDomain& domain, const TraceOptions& o, TraceStats& stats)
      : field_(field),
        domain_(domain),
        o_(o),
        stats_(stats),
        land_(domain.land),
        water_(domain.water),
        parks_(domain.parks) {
    h_ = o.step > 0.0 ? o.step : 0.5 * field.cellSize();
    referenceR_ = field.medianMagnitude();
    lo_ = field.origin();
    hi_ = field.vertex(field.width() - 1, field.height() - 1);
    maxLength_ = o.maxLength > 0.0 ? o.maxLength : 2.0 * distance(lo_, hi_);
    for (int l = 0; l < 2; ++l)
      for (int f = 0; f < 2; ++f) points_[l][f].init(lo_, hi_, base(static_cast<StreetLevel>(l)));
    all_.init(lo_, hi_, o.minorDsep);
    major_.init(lo_, hi_, o.minorDsep);
  }

  void run(const std::vector<Vec2>& seeds, const Progress& progress) {
    for (const LineString& l : domain_.existing)
      if (l.size() >= 2) insertExisting(l);
    traceLevel(StreetLevel::Major, seeds, subProgress(progress, 0.0, o_.minorRoads ? 0.4 : 1.0));
    if (o_.minorRoads) {
      // Minor roads are traced region by region, the major roads bounding the regions (§12): their
      // seeds lie on each side of every major road, every minor d_sep, and a minor road ends where it
      // meets a major road (a T-junction). The regions on the two sides are seeded independently, so
      // the two sides start half a spacing apart rather than lining up into crossings [INFERENCE].
      std::vector<std::pair<Vec2, int>> onMajor;
      for (const Street& s : streets_) {
        placeSeeds(s, StreetLevel::Minor, onMajor, 0.0, o_.sideOffset);
        placeSeeds(s, StreetLevel::Minor, onMajor, 0.5, -o_.sideOffset);
      }
      std::vector<Vec2> minorSeeds;
      traceLevel(StreetLevel::Minor, minorSeeds, subProgress(progress, 0.4, 1.0), onMajor);
    }
    connectExistingEnds();
    reportProgress(progress, 1.0, "tracing");
  }

  std::vector<Street> streets_;

 private:
  double base(StreetLevel l) const { return l == StreetLevel::Major ? o_.majorDsep : o_.minorDsep; }

  /// §11: d_sep(p) = d_sep (1 + (maxFactor − 1)(1 − P)^γ), × parkFactor in parks.
  double dsep(StreetLevel l, const Vec2& p) const {
    double f = 1.0;
    if (domain_.densitySpec) {
      const Vec2 px = domain_.densitySpec->transform.worldToPixel(p);
      const int i = static_cast<int>(std::floor(px.x)), j = static_cast<int>(std::floor(px.y));
      const double P =
          domain_.density.inside(i, j) ? std::clamp<double>(domain_.density.at(i, j), 0.0, 1.0) : 0.0;
      f = 1.0 + (o_.densityMaxFactor - 1.0) * std::pow(1.0 - P, o_.densityGamma);
    }
    if (!parks_.empty() && parks_.contains(p)) f *= o_.parkFactor;
    return base(l) * f;
  }

  bool onLand(const Vec2& p) const { return (land_.empty() || land_.contains(p)) && !water_.contains(p); }

  /// The family's unit eigenvector at p, aligned with `ref` (§8.2: E·V_pre >= 0); false at a degenerate
  /// point.
  bool eig(const Vec2& p, int family, const Vec2& ref, Vec2& out) const {
    const Tensor t = field_.sample(p);
    if (t.magnitude() <= o_.degenerateEpsilon * referenceR_ || t.magnitude() == 0.0) return false;
    out = family == 0 ? t.major() : t.minor();
    if (dot(out, ref) < 0.0) out = out * -1.0;
    return true;
  }

  /// One classical RK4 step of length h along the family, aligned at every stage.
  bool step(const Vec2& p, const Vec2& dir, int family, Vec2& q) const {
    Vec2 k1, k2, k3, k4;
    if (!eig(p, family, dir, k1) || !eig(p + k1 * (h_ / 2), family, k1, k2) ||
        !eig(p + k2 * (h_ / 2), family, k2, k3) || !eig(p + k3 * h_, family, k3, k4))
      return false;
    const Vec2 v = (k1 + k2 * 2.0 + k3 * 2.0 + k4) / 6.0;
    const double len = length(v);
    if (len == 0.0) return false;
    q = p + v * (h_ / len);
    return true;
  }

  /// Fraction of p→q before it leaves the land (boundary or water), > 1 when it stays.
  double exitFraction(const Vec2& p, const Vec2& q) const {
    return std::min(land_.firstCrossing(p, q), water_.firstCrossing(p, q));
  }

  /// Closer than r to a street of the level and family; a minor road also checks the major roads of its
  /// family, within rMajor (default r).
  bool tooClose(StreetLevel l, int family, const Vec2& p, double r, double rMajor = -1.0) const {
    if (points_[static_cast<int>(l)][family].anyWithin(p, r)) return true;
    return l == StreetLevel::Minor && points_[0][family].anyWithin(p, rMajor < 0.0 ? r : rMajor);
  }

  /// §8.3 look-ahead: keep integrating (ignoring criteria 4 and 5) for d_lookahead; keep the part up
  /// to the first crossing of any street, else try the straight continuation; else nothing.
  bool lookAhead(StreetLevel l, int family, LineString& pts, Vec2 dir) {
    const double reach = o_.lookaheadRatio * dsep(l, pts.back());
    if (reach <= 0.0) return false;
    LineString ext;
    Vec2 p = pts.back();
    double travelled = 0.0;
    while (travelled < reach) {
      Vec2 q;
      if (!step(p, dir, family, q)) break;
      if (exitFraction(p, q) <= 1.0 || !onLand(q)) break;
      const double t = all_.firstCrossing(p, q);
      if (t <= 1.0) {
        ext.push_back(p + (q - p) * t);
        pts.insert(pts.end(), ext.begin(), ext.end());
        return true;
      }
      ext.push_back(q);
      travelled += distance(p, q);
      dir = q - p;
      p = q;
    }
    // Straight continuation from the stop.
    const Vec2 from = pts.back();
    const Vec2 d = dir / std::max(length(dir), 1e-300);
    const Vec2 to = from + d * reach;
    const double t = all_.firstCrossing(from, to, 1e-9);
    if (t <= 1.0 && exitFraction(from, to) > t && onLand(from + (to - from) * (0.5 * t))) {
      pts.push_back(from + (to - from) * t);
      return true;
    }
    return false;
  }

  Half traceHalf(const Vec2& seed, StreetLevel l, int family, double sign) {
    Half half;
    half.points.push_back(seed);
    Vec2 dir;
    if (!eig(seed, family, {1.0, 0.0}, dir)) {
      half.stop = Stop::Degenerate;
      return half;
    }
    dir = dir * sign;
    Vec2 p = seed;
    double travelled = 0.0;
    const double loopEps = o_.loopRatio * o_.dtestRatio * base(l);
    for (bool first = true;; first = false) {
      Vec2 q;
      if (!step(p, dir, family, q)) {
        half.stop = Stop::Degenerate;
        return half;
      }
      const double tb = exitFraction(p, q);
      if (tb <= 1.0) {
        half.points.push_back(p + (q - p) * tb);
        half.stop = Stop::Boundary;
        return half;
      }
      if (!onLand(q)) {  // left through the very point it started on (a seed on the boundary)
        half.stop = Stop::Boundary;
        return half;
      }
      if (l == StreetLevel::Minor) {
        const double tm = major_.firstCrossing(p, q, first ? 1e-6 : 0.0);
        if (tm <= 1.0) {
          half.points.push_back(p + (q - p) * tm);
          half.stop = Stop::Junction;
          return half;
        }
      }
      travelled += h_;
      if (travelled > 2.0 * base(l) && distanceToSegment(seed, p, q) < loopEps) {
        half.points.push_back(seed);
        half.stop = Stop::Loop;
        return half;
      }
      const bool close = tooClose(l, family, q, o_.dtestRatio * dsep(l, q));
      if (close || travelled > maxLength_) {
        half.stop = close ? Stop::Close : Stop::Length;
        if (lookAhead(l, family, half.points, q - p)) {
          ++stats_.lookaheadJoins;
          half.stop = Stop::Junction;
        }
        return half;
      }
      half.points.push_back(q);
      dir = q - p;
      p = q;
    }
  }

  bool validSeed(const Vec2& s, StreetLevel l, int family) const {
    const double d = dsep(l, s) * (1.0 - 1e-6);
    if (!onLand(s) || tooClose(l, family, s, d, o_.majorClearanceRatio * d)) return false;
    const double margin = o_.edgeSeedRatio * h_;
    return !(margin > 0.0) || ((land_.empty() || land_.distanceToEdge(s, margin) >= margin) &&
                               water_.distanceToEdge(s, margin) >= margin);
  }

  /// Traces both directions from s and joins them through s. A minor road that joins a street at both
  /// ends stops d_test short of one of them instead, each end with chance stopShortShare (drawn per
  /// end from the run seed and the trace's number, so the network does not depend on threads).
  LineString trace(const Vec2& s, StreetLevel l, int family) {
    const std::uint64_t index = traces_++;
    Half forward = traceHalf(s, l, family, 1.0);
    if (forward.stop == Stop::Loop) return forward.points;
    Half backward = traceHalf(s, l, family, -1.0);
    LineString line(backward.points.rbegin(), backward.points.rend());
    line.insert(line.end(), forward.points.begin() + 1, forward.points.end());
    if (l == StreetLevel::Minor && o_.stopShortShare > 0.0) {
      auto stopsShort = [&](std::uint64_t end) {
        return unitDraw(o_.seed ^ 0x5707'5402ULL, 2 * index + end) < o_.stopShortShare;
      };
      // Only a street that joins streets at both ends may stop short, and at one end only: it stays
      // attached by the other (a cul-de-sac), never a street cut off from the network.
      const bool both = forward.stop == Stop::Junction && backward.stop == Stop::Junction;
      const bool forwardShort = both && stopsShort(0), backwardShort = both && !forwardShort && stopsShort(1);
      if (forwardShort) line = cutTail(line, o_.dtestRatio * dsep(l, line.back()));
      if (backwardShort) {
        std::reverse(line.begin(), line.end());
        line = cutTail(line, o_.dtestRatio * dsep(l, line.back()));
        std::reverse(line.begin(), line.end());
      }
    }
    return line;
  }

  /// The line without its last `gap` metres (a single point when it is shorter).
  static LineString cutTail(const LineString& line, double gap) {
    return headOfLength(line, length(line) - gap);
  }

  /// The family a road running along `dir` at p follows: the eigenvector closer to its direction.
  int familyAlong(const Vec2& p, const Vec2& dir) const {
    const Tensor t = field_.sample(p);
    if (t.magnitude() == 0.0) return 0;
    return std::abs(dot(t.major(), dir)) >= std::abs(dot(t.minor(), dir)) ? 0 : 1;
  }

  /// An existing road (§14) acts as a major road of the family it follows, segment by segment: its
  /// points, one per integration step like a traced road's, keep that family's roads d_sep away, and
  /// minor roads end on it.
  void insertExisting(const LineString& line) {
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
      const Vec2 a = line[i], b = line[i + 1];
      const int family = familyAlong((a + b) * 0.5, b - a);
      const int steps = std::max(1, static_cast<int>(std::ceil(distance(a, b) / h_)));
      for (int k = 0; k < steps; ++k) points_[0][family].add(a + (b - a) * (static_cast<double>(k) / steps));
      all_.add(a, b);
      major_.add(a, b);
    }
    points_[0][familyAlong(line.back(), line.back() - line[line.size() - 2])].add(line.back());
    streets_.push_back({line, StreetLevel::Existing, 0});
  }

  /// §14 "Connect": an existing road that stops inside the land without meeting another (the end of
  /// the roads the user chose to keep, not a mapped cul-de-sac, which the caller cannot tell apart)
  /// is continued along the field by the look-ahead rule of a major road (it acts as one) until it
  /// meets a street; it stays a dead end when none lies within the look-ahead distance.
  void connectExistingEnds() {
    std::map<std::pair<double, double>, int> lineCount;
    const std::size_t existing = domain_.existing.size();
    for (const LineString& l : domain_.existing) {
      std::set<std::pair<double, double>> own;
      for (const Vec2& v : l) own.insert({v.x, v.y});
      for (const auto& v : own) ++lineCount[v];
    }
    std::vector<LineString> extensions;
    for (std::size_t i = 0; i < existing; ++i) {
      const LineString& l = domain_.existing[i];
      if (l.size() < 2 || l.front() == l.back()) continue;
      for (int end = 0; end < 2; ++end) {
        const Vec2 p = end ? l.back() : l.front(), prev = end ? l[l.size() - 2] : l[1];
        if (lineCount[{p.x, p.y}] > 1 || !onLand(p)) continue;
        const Vec2 dir = p - prev;
        const int family = familyAlong(p, dir);
        Vec2 aligned;
        if (!eig(p, family, dir, aligned)) continue;
        LineString pts{p};
        if (lookAhead(StreetLevel::Major, family, pts, aligned) && pts.size() >= 2) extensions.push_back(pts);
      }
    }
    for (const LineString& e : extensions) {
      ++stats_.lookaheadJoins;
      insert(e, StreetLevel::Major, familyAlong(e.front(), e[1] - e.front()));
    }
  }

  void insert(const LineString& line, StreetLevel l, int family) {
    for (const Vec2& p : line) points_[static_cast<int>(l)][family].add(p);
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
      all_.add(line[i], line[i + 1]);
      if (l == StreetLevel::Major) major_.add(line[i], line[i + 1]);
    }
    streets_.push_back({line, l, family});
  }

  /// Seeds for the other family (or, for minor roads on a major road, the crossing family) every
  /// d_sep along a street (§9.1 step 2).
  /// `phase`: the first seed lies phase × d_sep from the start; `offset`: seeds lie this far to the
  /// left (negative: right) of the street.
  void placeSeeds(const Street& s, StreetLevel l, std::vector<std::pair<Vec2, int>>& out, double phase = 0.0,
                  double offset = 0.0) const {
    const bool existing = s.level == StreetLevel::Existing;
    double next = phase * dsep(l, s.line.front()), at = 0.0;
    for (std::size_t i = 0; i + 1 < s.line.size(); ++i) {
      const Vec2 a = s.line[i], b = s.line[i + 1];
      const double len = distance(a, b);
      if (len <= 0.0) continue;
      const Vec2 normal{-(b.y - a.y) / len, (b.x - a.x) / len};
      while (next <= at + len) {
        const Vec2 p = a + (b - a) * ((next - at) / len) + normal * offset;
        out.push_back({p, 1 - (existing ? familyAlong(p, b - a) : s.family)});
        next += dsep(l, p);
      }
      at += len;
    }
  }

  void traceLevel(StreetLevel l, const std::vector<Vec2>& seeds, const Progress& progress,
                  const std::vector<std::pair<Vec2, int>>& initial = {}) {
    std::deque<Vec2> queue[2];
    for (const Vec2& s : seeds) queue[0].push_back(s), queue[1].push_back(s);
    for (const auto& [p, f] : initial) queue[f].push_back(p);
    // Candidates covering the land every d_sep / 2, by priority ω = e^(−d_b/λ) (§9.2, §9.3).
    std::vector<std::pair<double, Vec2>> candidates;
    const double spacing = 0.5 * base(l), lambda = o_.priorityScaleRatio * base(l);
    for (double y = lo_.y + spacing / 2; y < hi_.y; y += spacing)
      for (double x = lo_.x + spacing / 2; x < hi_.x; x += spacing) {
        const Vec2 p{x, y};
        if (!onLand(p)) continue;
        const double db = water_.empty() ? std::numeric_limits<double>::infinity()
                                         : water_.distanceToEdge(p, 20.0 * lambda);
        candidates.push_back({std::exp(-db / lambda), p});
      }
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const auto& a, const auto& b) { return a.first > b.first; });
    std::size_t next = 0;
    int family = 0;
    ProgressTicker ticker(progress, l == StreetLevel::Major ? "major roads" : "minor roads",
                          2 * candidates.size());
    for (;;) {
      if (queue[family].empty()) family = 1 - family;
      if (queue[family].empty()) {
        // Both queues empty: the next candidate that is a valid seed for either family.
        bool found = false;
        while (!found && next < 2 * candidates.size()) {
          const Vec2 p = candidates[next / 2].second;
          const int f = static_cast<int>(next % 2);
          ++next;
          ticker.tick();
          if (validSeed(p, l, f)) queue[f].push_back(p), family = f, found = true;
        }
        if (!found) break;
      }
      const Vec2 s = queue[family].front();
      queue[family].pop_front();
      ++stats_.seedsTried;
      if (!validSeed(s, l, family)) continue;
      LineString line = trace(s, l, family);
      if (length(line) < o_.minLengthRatio * dsep(l, s)) {
        ++stats_.droppedShort;
        family = 1 - family;
        continue;
      }
      insert(line, l, family);
      std::vector<std::pair<Vec2, int>> more;
      placeSeeds(streets_.back(), l, more);
      for (const auto& [p, f] : more) queue[f].push_back(p);
      family = 1 - family;
    }
    ticker.finish();
  }

  const TensorField& field_;
  const TraceDomain& domain_;
  TraceOptions o_;
  TraceStats& stats_;
  PolygonIndex land_, water_, parks_;
  double h_ = 1.0, referenceR_ = 0.0, maxLength_ = 0.0;
  std::uint64_t traces_ = 0;  ///< lines traced so far (numbers the stop-short draws)
  Vec2 lo_, hi_;
  PointGrid points_[2][2];
  SegmentGrid all_, major_;
};

}  // namespace

std::vector<Street> traceStreets(const TensorField& field, const TraceDomain& domain,
                                 const std::vector<Vec2>& seeds, const TraceOptions& options,
                                 TraceStats* stats, const Progress& progress) {
  if (!(options.majorDsep > 0.0) || !(options.minorDsep > 0.0))
    throw invalidOption("d_sep must be > 0 (major " + std::to_string(options.majorDsep) + ", minor " +
                        std::to_string(options.minorDsep) + ")");
  if (!(options.dtestRatio > 0.0) || options.dtestRatio > 1.0)
    throw invalidOption("d_test must lie in (0, d_sep]: the d_test ratio " +
                        std::to_string(options.dtestRatio) + " is not in (0, 1]");
  TraceStats local;
  Tracer tracer(field, domain, options, stats ? *stats : local);
  tracer.run(seeds, progress);
  return std::move(tracer.streets_);
}

}  // namespace urbanvec::streets
