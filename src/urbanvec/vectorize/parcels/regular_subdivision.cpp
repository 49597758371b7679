// Spec §3 E2 (thesis §3.4.3 "Regular Subdivision", paper §3.4.1) with the [INFERENCE] algorithm of the
// spec and its resolutions Q16 (aspect rule against the 0.25 threshold), Q17 (road-facing = on the
// curb-derived boundary, merged contiguously), Q18 (the transferred cut is the chord nearest the
// sampled point), Q19 (70% measured on the simulated block) and Q20 (smallest simulated parcel).
#include "urbanvec/vectorize/parcels/regular_subdivision.hpp"

#include <algorithm>
#include <cmath>

#include "urbanvec/core/topology_simplify.hpp"
#include "urbanvec/vectorize/parcels/spine_subdivision.hpp"

namespace urbanvec::vectorize::parcels {

namespace {

constexpr double kOvershoot = 1e-7;  ///< cut overshoot past the parcel boundary so noding closes it, cells

double aspectOf(const Polygon& p) {
  return orientedBox(p).aspect();
}

}  // namespace

RoadFrontage::RoadFrontage(const geos::Context& geos, const MultiLineString& roadFacing, double tolerance)
    : geos_(geos), tolerance_(tolerance) {
  for (const LineString& line : roadFacing)
    for (size_t i = 0; i + 1 < line.size(); ++i)
      if (line[i] != line[i + 1]) segments_.push_back({line[i], line[i + 1]});
  if (segments_.empty()) return;
  buildGrid();
  geos::GeomPtr lines = geos.multiLineString(roadFacing);
  band_ = geos.own(GEOSBufferWithStyle_r(geos.handle(), lines.get(), tolerance, 2, GEOSBUF_CAP_FLAT,
                                         GEOSBUF_JOIN_MITRE, 2.0),
                   "buffer");
}

void RoadFrontage::buildGrid() {
  double minX = 1e300, minY = 1e300, maxX = -1e300, maxY = -1e300, totalLength = 0.0;
  for (const auto& s : segments_) {
    for (const Vec2& p : s) {
      minX = std::min(minX, p.x);
      minY = std::min(minY, p.y);
      maxX = std::max(maxX, p.x);
      maxY = std::max(maxY, p.y);
    }
    totalLength += urbanvec::distance(s[0], s[1]);
  }
  const double count = static_cast<double>(segments_.size());
  // Cells at least one mean segment long and at most about 2 per segment (the extents are at most
  // the total length), so a cell holds a few segments and the grid stays small.
  cellSize_ = std::max({totalLength / count, std::sqrt((maxX - minX) * (maxY - minY) / (2.0 * count)), 1e-6});
  gridOrigin_ = {minX, minY};
  columns_ = static_cast<int>((maxX - minX) / cellSize_) + 1;
  rows_ = static_cast<int>((maxY - minY) / cellSize_) + 1;
  auto cellRange = [&](const std::array<Vec2, 2>& s, int& c0, int& c1, int& r0, int& r1) {
    c0 = static_cast<int>((std::min(s[0].x, s[1].x) - minX) / cellSize_);
    c1 = std::min(columns_ - 1, static_cast<int>((std::max(s[0].x, s[1].x) - minX) / cellSize_));
    r0 = static_cast<int>((std::min(s[0].y, s[1].y) - minY) / cellSize_);
    r1 = std::min(rows_ - 1, static_cast<int>((std::max(s[0].y, s[1].y) - minY) / cellSize_));
  };
  cellStart_.assign(static_cast<size_t>(columns_) * rows_ + 1, 0);
  int c0, c1, r0, r1;
  for (const auto& s : segments_) {
    cellRange(s, c0, c1, r0, r1);
    for (int c = c0; c <= c1; ++c)
      for (int r = r0; r <= r1; ++r) ++cellStart_[static_cast<size_t>(c) * rows_ + r + 1];
  }
  for (size_t k = 1; k < cellStart_.size(); ++k) cellStart_[k] += cellStart_[k - 1];
  cellSegments_.resize(cellStart_.back());
  std::vector<std::uint32_t> fill(cellStart_.begin(), cellStart_.end() - 1);
  for (size_t i = 0; i < segments_.size(); ++i) {
    cellRange(segments_[i], c0, c1, r0, r1);
    for (int c = c0; c <= c1; ++c)
      for (int r = r0; r <= r1; ++r)
        cellSegments_[fill[static_cast<size_t>(c) * rows_ + r]++] = static_cast<std::uint32_t>(i);
  }
  lastSeen_.assign(segments_.size(), 0);
}

void RoadFrontage::segmentsAlong(const Vec2& a, const Vec2& b, double margin) const {
  candidates_.clear();
  if (++query_ == 0) {  // the stamps wrapped around: forget them
    std::fill(lastSeen_.begin(), lastSeen_.end(), 0);
    query_ = 1;
  }
  const double edgeMinX = std::min(a.x, b.x), edgeMaxX = std::max(a.x, b.x);
  const double edgeMinY = std::min(a.y, b.y), edgeMaxY = std::max(a.y, b.y);
  const double gridMaxX = gridOrigin_.x + columns_ * cellSize_, gridMaxY = gridOrigin_.y + rows_ * cellSize_;
  if (edgeMaxX + margin < gridOrigin_.x || edgeMinX - margin > gridMaxX ||
      edgeMaxY + margin < gridOrigin_.y || edgeMinY - margin > gridMaxY)
    return;
  auto column = [&](double x) {
    return std::clamp(static_cast<int>(std::floor((x - gridOrigin_.x) / cellSize_)), 0, columns_ - 1);
  };
  auto row = [&](double y) {
    return std::clamp(static_cast<int>(std::floor((y - gridOrigin_.y) / cellSize_)), 0, rows_ - 1);
  };
  const int c0 = column(edgeMinX - margin), c1 = column(edgeMaxX + margin);
  const double dx = b.x - a.x;
  for (int c = c0; c <= c1; ++c) {
    // Within a column, visit only the rows the edge crosses there (a long diagonal edge would
    // otherwise sweep its whole bounding box).
    double lowY = edgeMinY, highY = edgeMaxY;
    if (c0 != c1 && dx != 0.0) {
      const double x0 = std::max(gridOrigin_.x + c * cellSize_ - margin, edgeMinX);
      const double x1 = std::min(gridOrigin_.x + (c + 1) * cellSize_ + margin, edgeMaxX);
      const double y0 = a.y + (x0 - a.x) / dx * (b.y - a.y), y1 = a.y + (x1 - a.x) / dx * (b.y - a.y);
      lowY = std::max(edgeMinY, std::min(y0, y1));
      highY = std::min(edgeMaxY, std::max(y0, y1));
    }
    const int r0 = row(lowY - margin), r1 = row(highY + margin);
    for (int r = r0; r <= r1; ++r) {
      const size_t cell = static_cast<size_t>(c) * rows_ + r;
      for (std::uint32_t k = cellStart_[cell]; k < cellStart_[cell + 1]; ++k) {
        const std::uint32_t segment = cellSegments_[k];
        if (lastSeen_[segment] == query_) continue;
        lastSeen_[segment] = query_;
        candidates_.push_back(segment);
      }
    }
  }
}

double RoadFrontage::longest(const Polygon& parcel) const {
  double best = longestOnRing(parcel.outer);
  for (const Ring& h : parcel.holes) best = std::max(best, longestOnRing(h));
  return best;
}

double RoadFrontage::longestOnRing(const Ring& ring) const {
  if (segments_.empty() || ring.size() < 3) return 0.0;
  const size_t n = ring.size() - 1;
  const double tol = tolerance_;
  // Covered intervals (in length units along each edge) from collinear road-facing segments, merged
  // per edge; edge i owns cover_[coverStart_[i], coverStart_[i + 1]).
  cover_.clear();
  coverStart_.assign(n + 1, 0);
  edgeLength_.assign(n, 0.0);
  double coveredTotal = 0.0;
  for (size_t i = 0; i < n; ++i) {
    coverStart_[i] = static_cast<std::uint32_t>(cover_.size());
    const Vec2 a = ring[i], b = ring[i + 1];
    const double len = urbanvec::distance(a, b);
    edgeLength_[i] = len;
    if (len <= 0.0) continue;
    const Vec2 d = (b - a) / len;
    const Vec2 nrm{-d.y, d.x};
    const double minX = std::min(a.x, b.x) - tol, maxX = std::max(a.x, b.x) + tol;
    const double minY = std::min(a.y, b.y) - tol, maxY = std::max(a.y, b.y) + tol;
    // A segment covers part of the edge only if a point of it lies within tol of the edge.
    segmentsAlong(a, b, tol + 1e-9);
    edgeCover_.clear();
    for (const std::uint32_t index : candidates_) {
      const auto& seg = segments_[index];
      if (std::max(seg[0].x, seg[1].x) < minX || std::min(seg[0].x, seg[1].x) > maxX ||
          std::max(seg[0].y, seg[1].y) < minY || std::min(seg[0].y, seg[1].y) > maxY)
        continue;
      if (std::fabs(dot(seg[0] - a, nrm)) > tol || std::fabs(dot(seg[1] - a, nrm)) > tol) continue;
      const double s0 = dot(seg[0] - a, d), s1 = dot(seg[1] - a, d);
      const double lo = std::max(0.0, std::min(s0, s1)), hi = std::min(len, std::max(s0, s1));
      if (hi > lo) edgeCover_.emplace_back(lo, hi);
    }
    std::sort(edgeCover_.begin(), edgeCover_.end());
    const size_t first = cover_.size();
    for (const auto& iv : edgeCover_) {
      if (cover_.size() > first && iv.first <= cover_.back().second + tol)
        cover_.back().second = std::max(cover_.back().second, iv.second);
      else
        cover_.push_back(iv);
    }
    for (size_t k = first; k < cover_.size(); ++k) coveredTotal += cover_[k].second - cover_[k].first;
  }
  coverStart_[n] = static_cast<std::uint32_t>(cover_.size());
  // Chain the covered pieces along the ring; two laps join a run across the ring's start.
  double best = 0.0, run = 0.0;
  for (size_t k = 0; k < 2 * n; ++k) {
    const size_t i = k % n;
    const size_t begin = coverStart_[i], end = coverStart_[i + 1];
    if (begin == end) {
      if (edgeLength_[i] > tol) run = 0.0;
      continue;
    }
    const double firstLength = cover_[begin].second - cover_[begin].first;
    run = cover_[begin].first <= tol ? run + firstLength : firstLength;
    best = std::max(best, run);
    for (size_t j = begin + 1; j < end; ++j) {
      run = cover_[j].second - cover_[j].first;
      best = std::max(best, run);
    }
    if (cover_[end - 1].second < edgeLength_[i] - tol) run = 0.0;
  }
  return std::min(best, coveredTotal);
}

double RoadFrontage::longestGeos(const Polygon& parcel) const {
  if (segments_.empty()) return 0.0;
  GEOSContextHandle_t h = geos_.handle();
  geos::GeomPtr polygon = geos_.polygon(parcel);
  geos::GeomPtr boundary = geos_.own(GEOSBoundary_r(h, polygon.get()), "boundary");
  geos::GeomPtr onRoad = geos_.own(GEOSIntersection_r(h, boundary.get(), band_.get()), "intersection");
  const MultiLineString pieces = geos_.toLines(onRoad.get());
  if (pieces.empty()) return 0.0;
  geos::GeomPtr merged = geos_.own(GEOSLineMerge_r(h, geos_.multiLineString(pieces).get()), "lineMerge");
  double best = 0.0;
  for (const LineString& l : geos_.toLines(merged.get())) best = std::max(best, length(l));
  return best;
}

bool RoadFrontage::within(const Vec2& p, double limit) const {
  if (segments_.empty()) return false;
  // The nearest point of a segment lies in its bounding box, so a box farther than the limit (plus a
  // margin for the rounding of the projection) cannot hold a segment within it.
  const double reach = limit + 1e-9;
  segmentsAlong(p, p, reach);
  for (const std::uint32_t index : candidates_) {
    const auto& s = segments_[index];
    if (p.x < std::min(s[0].x, s[1].x) - reach || p.x > std::max(s[0].x, s[1].x) + reach ||
        p.y < std::min(s[0].y, s[1].y) - reach || p.y > std::max(s[0].y, s[1].y) + reach)
      continue;
    if (distanceToSegment(p, s[0], s[1]) <= limit) return true;
  }
  return false;
}

SplitRules splitRules(const SimBlockSummary& sim, const RegularSubdivisionOptions& options) {
  SplitRules rules;
  double smallest = 0.0, residential = 0.0;
  for (const SimParcel& p : sim.parcels) {
    if (smallest == 0.0 || p.cells < smallest) smallest = p.cells;
    if (p.use == LandUse::Residential) residential += p.cells;
  }
  rules.minArea = options.minAreaFraction * smallest;
  rules.minFrontage = options.minFrontage;
  rules.aspectThreshold = options.aspectThreshold;
  rules.compareParentAspect = options.compareParentAspect;
  rules.residentialRule = sim.area > 0.0 && residential / sim.area >= options.residentialShare;
  rules.minChildShare = options.minChildShare;
  return rules;
}

std::string_view verdictName(SplitVerdict verdict) {
  switch (verdict) {
    case SplitVerdict::Accepted:
      return "accepted";
    case SplitVerdict::TooSmall:
      return "minimum parcel size";
    case SplitVerdict::NoRoadAccess:
      return "road access";
    case SplitVerdict::TooRectangular:
      return "limited rectangularity";
    case SplitVerdict::UnequalResidential:
      return "residential size variation";
    case SplitVerdict::BadGeometry:
      return "cut geometry";
  }
  return "unknown";
}

std::string SplitStats::shortfallReason() const {
  int worst = 1;
  for (int i = 2; i < 6; ++i)
    if (rejected[i] > rejected[worst]) worst = i;
  return "no acceptable split (mostly " + std::string(verdictName(static_cast<SplitVerdict>(worst))) + ")";
}

SplitVerdict checkSplit(const Polygon& parent, const Polygon& a, const Polygon& b, const SplitRules& rules,
                        const RoadFrontage& frontage) {
  return checkSplit(area(parent), aspectOf(parent), a, b, rules, frontage);
}

SplitVerdict checkSplit(double parentArea, double parentAspect, const Polygon& a, const Polygon& b,
                        const SplitRules& rules, const RoadFrontage& frontage) {
  // Each ring's signed area once: the children's areas (as area() sums them) and the orientation their
  // second moments need.
  thread_local std::vector<double> ringsA, ringsB;
  auto ringAreas = [](const Polygon& p, std::vector<double>& rings) {
    rings.clear();
    rings.push_back(signedArea(p.outer));
    double total = std::fabs(rings.back());
    for (const Ring& hole : p.holes) {
      rings.push_back(signedArea(hole));
      total -= std::fabs(rings.back());
    }
    return total;
  };
  const double areaA = ringAreas(a, ringsA), areaB = ringAreas(b, ringsB), areaP = parentArea;
  if (areaA < rules.minArea || areaB < rules.minArea || areaA <= 0.0 || areaB <= 0.0)
    return SplitVerdict::TooSmall;
  const double aspectA = orientedBox(a, ringsA.data()).aspect(),
               aspectB = orientedBox(b, ringsB.data()).aspect();
  if (rules.compareParentAspect) {
    const bool ok = parentAspect >= rules.aspectThreshold
                        ? (aspectA >= parentAspect && aspectB >= parentAspect)
                        : (aspectA > parentAspect && aspectB > parentAspect);
    if (!ok) return SplitVerdict::TooRectangular;
  } else {
    const bool ok = parentAspect >= rules.aspectThreshold
                        ? (aspectA >= rules.aspectThreshold && aspectB >= rules.aspectThreshold)
                        : (aspectA > parentAspect && aspectB > parentAspect);
    if (!ok) return SplitVerdict::TooRectangular;
  }
  if (rules.residentialRule && (areaA < rules.minChildShare * areaP || areaB < rules.minChildShare * areaP))
    return SplitVerdict::UnequalResidential;
  // Road access last: it is the only constraint that needs more than the polygons' moments.
  if (frontage.longest(a) < rules.minFrontage || frontage.longest(b) < rules.minFrontage)
    return SplitVerdict::NoRoadAccess;
  return SplitVerdict::Accepted;
}

SubdivisionParcel::SubdivisionParcel(Polygon p) : polygon(std::move(p)), area(urbanvec::area(polygon)) {}

void prepare(SubdivisionParcel& parcel, const RegularSubdivisionOptions& options,
             const RoadFrontage& frontage, const geos::Context& geos) {
  parcel.prepared = true;
  parcel.aspect = aspectOf(parcel.polygon);
  // GEOS's TopologyPreservingSimplifier rules in plain code (core/topology_simplify.hpp): the same
  // copy without a GEOS geometry and two quadtrees per parcel (issue 21).
  Polygon simplified;
  if (options.simplifyTolerance > 0.0)
    simplified = simplifyPreservingTopology(parcel.polygon, options.simplifyTolerance);
  if (options.simplifyTolerance <= 0.0 || !(area(simplified) > 0.0)) simplified = parcel.polygon;
  // An edge of the simplified copy faces the road when it runs along road-facing lines, i.e. its
  // quarter points all lie within the simplification tolerance of them.
  const double near = options.simplifyTolerance + options.frontageTolerance;
  auto scanRing = [&](const Ring& ring) {
    for (size_t i = 0; i + 1 < ring.size(); ++i) {
      const Vec2 a = ring[i], b = ring[i + 1];
      if (distance(a, b) <= 1e-9) continue;
      bool facing = true;
      for (double t : {0.25, 0.5, 0.75})
        if (!frontage.within(a + (b - a) * t, near)) facing = false;
      if (facing) parcel.roadEdges.push_back({a, b});
    }
  };
  scanRing(simplified.outer);
  for (const Ring& h : simplified.holes) scanRing(h);
}

namespace {

/// Whether p lies inside the closed ring (crossing number; a point on the ring may go either way).
bool insideRing(const Vec2& p, const Ring& ring) {
  bool inside = false;
  for (size_t i = 0; i + 1 < ring.size(); ++i) {
    const Vec2& a = ring[i];
    const Vec2& b = ring[i + 1];
    if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x)) inside = !inside;
  }
  return inside;
}

enum class LineSplit {
  Split,       ///< two children in `out`
  NoSplit,     ///< the piece joins two different rings, so cutting along it leaves one piece
  Degenerate,  ///< left to GEOS
};

/// Splits a polygon by the piece of the line q + s·dir that lies inside it nearest q, when that piece
/// runs from the outer ring to the outer ring (each hole goes to the side that contains it) or from a
/// hole back to the same hole (it cuts off the pocket of parcel in a bay of the hole). Degenerate
/// cases are left to GEOS: the line through a vertex or along an edge of any ring, or a hole whose
/// side is unclear because it touches a ring of the cut.
LineSplit splitPolygonByLine(const Polygon& polygon, const Vec2& q, const Vec2& dir,
                             std::array<Polygon, 2>& out) {
  struct Crossing {
    double s;
    size_t ring;  ///< 0 for the outer ring, h + 1 for hole h
    size_t edge;
    Vec2 point;
  };
  thread_local std::vector<Crossing> crossings;  // reused: one split test per try and parcel
  crossings.clear();
  auto addCrossings = [&](const Ring& ring, size_t ringIndex) {
    double next = ring.empty() ? 0.0 : cross(ring[0] - q, dir);
    for (size_t i = 0; i + 1 < ring.size(); ++i) {
      const Vec2 p0 = ring[i], e = ring[i + 1] - ring[i];
      // Both ends clearly on one side of the line (most edges): no crossing, not along the edge and
      // not through a vertex, so the tests below would skip the edge too; their thresholds are far
      // inside these margins.
      const double side0 = next, side1 = cross(ring[i + 1] - q, dir);
      next = side1;
      if ((side0 > 1e-9 && side1 > 1e-9) || (side0 < -1e-9 && side1 < -1e-9)) {
        const double near = std::min(std::fabs(side0), std::fabs(side1));
        if (near > 1e-6 * std::max(std::fabs(side0), std::fabs(side1))) continue;
      }
      const double denom = cross(dir, e);
      const double scale = length(e);
      if (scale <= 0.0) continue;
      if (std::fabs(denom) <= 1e-12 * scale) {
        if (std::fabs(side0) <= 1e-9) return false;  // along the edge
        continue;
      }
      const double u = side0 / denom;
      if (u < -1e-12 || u > 1.0 + 1e-12) continue;
      if (u < 1e-9 || u > 1.0 - 1e-9) return false;  // through a vertex
      const double s = cross(p0 - q, e) / denom;
      crossings.push_back({s, ringIndex, i, p0 + e * u});
    }
    return true;
  };
  if (!addCrossings(polygon.outer, 0)) return LineSplit::Degenerate;
  for (size_t h = 0; h < polygon.holes.size(); ++h)
    if (!addCrossings(polygon.holes[h], h + 1)) return LineSplit::Degenerate;
  // Inside the polygon the line runs between crossings 0-1, 2-3, ... of all rings in order along it.
  if (crossings.size() < 2 || crossings.size() % 2 != 0) return LineSplit::Degenerate;
  std::sort(crossings.begin(), crossings.end(),
            [](const Crossing& a, const Crossing& b) { return a.s < b.s; });
  size_t pick = 0;
  double best = 1e300;
  for (size_t k = 0; k + 1 < crossings.size(); k += 2) {
    const double lo = crossings[k].s, hi = crossings[k + 1].s;
    const double d = (lo <= 0.0 && hi >= 0.0) ? 0.0 : std::min(std::fabs(lo), std::fabs(hi));
    if (d < best) {
      best = d;
      pick = k;
    }
  }
  if (crossings[pick + 1].s - crossings[pick].s <= 1e-9) return LineSplit::Degenerate;
  const Crossing& a = crossings[pick];
  const Crossing& b = crossings[pick + 1];
  if (a.ring != b.ring) return LineSplit::NoSplit;
  const Ring& ring = a.ring == 0 ? polygon.outer : polygon.holes[a.ring - 1];
  const size_t n = ring.size() - 1;
  auto walk = [&](const Crossing& from, const Crossing& to) {
    Ring r{from.point};
    r.reserve(n + 3);
    for (size_t i = (from.edge + 1) % n;; i = (i + 1) % n) {
      r.push_back(ring[i]);
      if (i == to.edge) break;
    }
    r.push_back(to.point);
    r.push_back(from.point);
    return r;
  };
  if (a.ring != 0) {
    // The piece runs from a hole back to the same hole across the mouth of a bay of it: the chord
    // and the arc of the hole around the bay close the pocket of parcel in the bay (the smaller of the
    // two rings: the other one also holds the hole), and the rest of the parcel gets the hole grown by
    // that pocket. The other holes go to the side that contains them.
    Ring first = walk(a, b), second = walk(b, a);
    const bool firstIsPocket = std::fabs(signedArea(first)) < std::fabs(signedArea(second));
    Ring& pocket = firstIsPocket ? first : second;
    Ring& grown = firstIsPocket ? second : first;
    const bool outerPositive = signedArea(polygon.outer) > 0.0, holePositive = signedArea(ring) > 0.0;
    if ((signedArea(pocket) > 0.0) != outerPositive) std::reverse(pocket.begin(), pocket.end());
    if ((signedArea(grown) > 0.0) != holePositive) std::reverse(grown.begin(), grown.end());
    out[0] = Polygon{std::move(pocket), {}};
    out[1] = Polygon{polygon.outer, {std::move(grown)}};
    for (size_t h = 0; h < polygon.holes.size(); ++h) {
      if (h + 1 == a.ring) continue;
      const Ring& hole = polygon.holes[h];
      const bool inFirst = insideRing(hole[0], out[0].outer), inSecond = insideRing(hole[1], out[0].outer);
      if (inFirst != inSecond) return LineSplit::Degenerate;
      out[inFirst ? 0 : 1].holes.push_back(hole);
    }
    return LineSplit::Split;
  }
  out[0] = Polygon{walk(a, b), {}};
  out[1] = Polygon{walk(b, a), {}};
  // The chord meets no hole, so each hole lies wholly on one side. A valid hole touches the outer ring
  // in at most one point, so two of its vertices agree on the side unless one lies on that point.
  for (const Ring& hole : polygon.holes) {
    const bool first = insideRing(hole[0], out[0].outer), second = insideRing(hole[1], out[0].outer);
    if (first != second) return LineSplit::Degenerate;
    out[first ? 0 : 1].holes.push_back(hole);
  }
  return LineSplit::Split;
}

}  // namespace

SplitVerdict trySplit(SubdivisionParcel& parcel, const SplitRules& rules,
                      const RegularSubdivisionOptions& options, const RoadFrontage& frontage,
                      const geos::Context& geos, Rng& rng, std::array<Polygon, 2>& out) {
  if (!parcel.prepared) prepare(parcel, options, frontage, geos);
  if (parcel.roadEdges.empty()) return SplitVerdict::NoRoadAccess;

  size_t edge = 0;
  if (options.lengthWeightedEdges) {
    std::vector<double> weights;
    for (const auto& e : parcel.roadEdges) weights.push_back(distance(e[0], e[1]));
    edge = std::discrete_distribution<size_t>(weights.begin(), weights.end())(rng);
  } else {
    edge = std::uniform_int_distribution<size_t>(0, parcel.roadEdges.size() - 1)(rng);
  }
  std::normal_distribution<double> position(0.5, options.positionSigma);
  double t = position(rng);
  for (int i = 0; i < 64 && (t <= 0.0 || t >= 1.0); ++i) t = position(rng);
  if (t <= 0.0 || t >= 1.0) t = 0.5;

  const Vec2 a = parcel.roadEdges[edge][0], b = parcel.roadEdges[edge][1];
  const Vec2 q = a + (b - a) * t;
  const Vec2 along = (b - a) / distance(a, b);
  const Vec2 normal{-along.y, along.x};

  // Transfer to the original: the piece of the perpendicular line inside the original parcel that is
  // nearest the sampled point (Q18). Plain code, GEOS in the degenerate cases.
  if (parcel.polygon.outer.size() >= 4) {
    std::array<Polygon, 2> children;
    const LineSplit split = splitPolygonByLine(parcel.polygon, q, normal, children);
    if (split == LineSplit::NoSplit) return SplitVerdict::BadGeometry;
    if (split == LineSplit::Split) {
      const SplitVerdict verdict =
          checkSplit(parcel.area, parcel.aspect, children[0], children[1], rules, frontage);
      if (verdict == SplitVerdict::Accepted) out = std::move(children);
      return verdict;
    }
  }
  double minX = 1e300, minY = 1e300, maxX = -1e300, maxY = -1e300;
  for (const Vec2& p : parcel.polygon.outer) {
    minX = std::min(minX, p.x);
    minY = std::min(minY, p.y);
    maxX = std::max(maxX, p.x);
    maxY = std::max(maxY, p.y);
  }
  const double reach = std::hypot(maxX - minX, maxY - minY) + 1.0;
  GEOSContextHandle_t h = geos.handle();
  geos::GeomPtr polygon = geos.polygon(parcel.polygon);
  geos::GeomPtr line = geos.lineString({q - normal * reach, q + normal * reach});
  geos::GeomPtr inside = geos.own(GEOSIntersection_r(h, line.get(), polygon.get()), "intersection");
  const MultiLineString pieces = geos.toLines(inside.get());
  const LineString* chord = nullptr;
  double best = 1e300;
  for (const LineString& piece : pieces) {
    for (size_t i = 0; i + 1 < piece.size(); ++i) {
      const double d = distanceToSegment(q, piece[i], piece[i + 1]);
      if (d < best) {
        best = d;
        chord = &piece;
      }
    }
  }
  if (!chord || length(*chord) <= 1e-9) return SplitVerdict::BadGeometry;
  const Vec2 s = chord->front(), e = chord->back();
  const Vec2 dir = (e - s) / distance(s, e);
  const MultiLineString cut{{s - dir * kOvershoot, e + dir * kOvershoot}};
  MultiPolygon faces = facesInside(geos, polygon.get(), cut);
  if (faces.size() != 2) return SplitVerdict::BadGeometry;
  const SplitVerdict verdict = checkSplit(parcel.area, parcel.aspect, faces[0], faces[1], rules, frontage);
  if (verdict == SplitVerdict::Accepted) {
    out[0] = std::move(faces[0]);
    out[1] = std::move(faces[1]);
  }
  return verdict;
}

bool subdivide(std::vector<SubdivisionParcel>& parcels, int target, const SplitRules& rules,
               const RegularSubdivisionOptions& options, const RoadFrontage& frontage,
               const geos::Context& geos, Rng& rng, SplitStats& stats) {
  while (static_cast<int>(parcels.size()) < target) {
    size_t largest = 0;
    for (size_t i = 1; i < parcels.size(); ++i)
      if (parcels[i].area > parcels[largest].area) largest = i;
    bool split = false;
    for (int attempt = 0; attempt < options.maxAttempts && !split; ++attempt) {
      size_t index = largest;
      if (attempt >= options.maxLargestAttempts && parcels.size() > 1) {
        index = std::uniform_int_distribution<size_t>(0, parcels.size() - 2)(rng);
        if (index >= largest) ++index;  // a random *other* parcel
      }
      std::array<Polygon, 2> children;
      const SplitVerdict verdict = trySplit(parcels[index], rules, options, frontage, geos, rng, children);
      if (verdict != SplitVerdict::Accepted) {
        ++stats.rejected[static_cast<int>(verdict)];
        continue;
      }
      ++stats.accepted;
      parcels[index] = SubdivisionParcel(std::move(children[0]));
      parcels.emplace_back(std::move(children[1]));
      split = true;
    }
    if (!split) return false;
  }
  return true;
}

}  // namespace urbanvec::vectorize::parcels
