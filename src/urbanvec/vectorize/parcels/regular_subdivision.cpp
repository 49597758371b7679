// Spec §3 E2 (thesis §3.4.3 "Regular Subdivision", paper §3.4.1) with the [INFERENCE] algorithm of the
// spec and its resolutions Q16 (aspect rule against the 0.25 threshold), Q17 (road-facing = on the
// curb-derived boundary, merged contiguously), Q18 (the transferred cut is the chord nearest the
// sampled point), Q19 (70% measured on the simulated block) and Q20 (smallest simulated parcel).
#include "urbanvec/vectorize/parcels/regular_subdivision.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <tuple>

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
  lines_ = roadFacing;
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

int RoadFrontage::column(double x) const {
  return std::clamp(static_cast<int>(std::floor((x - gridOrigin_.x) / cellSize_)), 0, columns_ - 1);
}

int RoadFrontage::row(double y) const {
  return std::clamp(static_cast<int>(std::floor((y - gridOrigin_.y) / cellSize_)), 0, rows_ - 1);
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
  coverRing(ring, ringCover_);
  return longestOfCover(ringCover_);
}

void RoadFrontage::coverEdge(const Vec2& a, const Vec2& b, RingCover& cover) const {
  // Covered intervals (in length units along the edge) from collinear road-facing segments, merged.
  const double tol = tolerance_;
  const double len = urbanvec::distance(a, b);
  cover.length.push_back(len);
  if (len > 0.0 && !segments_.empty()) {
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
    const size_t first = cover.intervals.size();
    for (const auto& iv : edgeCover_) {
      if (cover.intervals.size() > first && iv.first <= cover.intervals.back().second + tol)
        cover.intervals.back().second = std::max(cover.intervals.back().second, iv.second);
      else
        cover.intervals.push_back(iv);
    }
  }
  cover.start.push_back(static_cast<std::uint32_t>(cover.intervals.size()));
}

void RoadFrontage::copyEdges(const RingCover& from, size_t first, size_t count, RingCover& cover) {
  if (count == 0) return;
  cover.length.insert(cover.length.end(), from.length.begin() + static_cast<std::ptrdiff_t>(first),
                      from.length.begin() + static_cast<std::ptrdiff_t>(first + count));
  const std::uint32_t begin = from.start[first],
                      shift = static_cast<std::uint32_t>(cover.intervals.size()) - begin;
  cover.intervals.insert(cover.intervals.end(), from.intervals.begin() + begin,
                         from.intervals.begin() + from.start[first + count]);
  for (size_t i = first + 1; i <= first + count; ++i) cover.start.push_back(from.start[i] + shift);
}

void RoadFrontage::coverRing(const Ring& ring, RingCover& cover) const {
  cover.clear();
  for (size_t i = 0; i + 1 < ring.size(); ++i) coverEdge(ring[i], ring[i + 1], cover);
}

double RoadFrontage::longestOfCover(const RingCover& cover) const {
  const size_t n = cover.edges();
  if (segments_.empty() || n < 2) return 0.0;
  const double tol = tolerance_;
  double coveredTotal = 0.0;
  for (const auto& iv : cover.intervals) coveredTotal += iv.second - iv.first;
  // Chain the covered pieces along the ring; two laps join a run across the ring's start.
  double best = 0.0, run = 0.0;
  for (size_t k = 0; k < 2 * n; ++k) {
    const size_t i = k % n;
    const size_t begin = cover.start[i], end = cover.start[i + 1];
    if (begin == end) {
      if (cover.length[i] > tol) run = 0.0;
      continue;
    }
    const double firstLength = cover.intervals[begin].second - cover.intervals[begin].first;
    run = cover.intervals[begin].first <= tol ? run + firstLength : firstLength;
    best = std::max(best, run);
    for (size_t j = begin + 1; j < end; ++j) {
      run = cover.intervals[j].second - cover.intervals[j].first;
      best = std::max(best, run);
    }
    if (cover.intervals[end - 1].second < cover.length[i] - tol) run = 0.0;
  }
  return std::min(best, coveredTotal);
}

double RoadFrontage::longestGeos(const Polygon& parcel) const {
  if (segments_.empty()) return 0.0;
  GEOSContextHandle_t h = geos_.handle();
  if (!band_) {  // only the checkers measure with GEOS: the band is built on first use (issue 21)
    geos::GeomPtr lines = geos_.multiLineString(lines_);
    band_ = geos_.own(
        GEOSBufferWithStyle_r(h, lines.get(), tolerance_, 2, GEOSBUF_CAP_FLAT, GEOSBUF_JOIN_MITRE, 2.0),
        "buffer");
  }
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
  // margin for the rounding of the projection) cannot hold a segment within it. The cells within that
  // reach of p are visited directly and the first segment within the limit ends the search (a
  // segment registered in two of them may be measured twice; issue 21).
  const double reach = limit + 1e-9;
  if (p.x + reach < gridOrigin_.x || p.x - reach > gridOrigin_.x + columns_ * cellSize_ ||
      p.y + reach < gridOrigin_.y || p.y - reach > gridOrigin_.y + rows_ * cellSize_)
    return false;
  const int c0 = column(p.x - reach), c1 = column(p.x + reach), r0 = row(p.y - reach), r1 = row(p.y + reach);
  for (int c = c0; c <= c1; ++c)
    for (int r = r0; r <= r1; ++r) {
      const size_t cell = static_cast<size_t>(c) * rows_ + r;
      for (std::uint32_t k = cellStart_[cell]; k < cellStart_[cell + 1]; ++k) {
        const auto& s = segments_[cellSegments_[k]];
        if (p.x < std::min(s[0].x, s[1].x) - reach || p.x > std::max(s[0].x, s[1].x) + reach ||
            p.y < std::min(s[0].y, s[1].y) - reach || p.y > std::max(s[0].y, s[1].y) + reach)
          continue;
        if (distanceToSegment(p, s[0], s[1]) <= limit) return true;
      }
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

namespace {

/// The four constraints in order: size, rectangularity, residential variation, then road access, the
/// costliest, last. `frontageOf(k)` measures child k's longest road frontage. The children's areas
/// and aspects are left in `areas` and `aspects` once computed.
template <class Frontage>
SplitVerdict checkChildren(double parentArea, double parentAspect, const Polygon& a, const Polygon& b,
                           const SplitRules& rules, Frontage&& frontageOf, std::array<double, 2>& areas,
                           std::array<double, 2>& aspects) {
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
  areas = {areaA, areaB};
  if (areaA < rules.minArea || areaB < rules.minArea || areaA <= 0.0 || areaB <= 0.0)
    return SplitVerdict::TooSmall;
  const double aspectA = orientedBox(a, ringsA.data()).aspect(),
               aspectB = orientedBox(b, ringsB.data()).aspect();
  aspects = {aspectA, aspectB};
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
  if (frontageOf(0) < rules.minFrontage || frontageOf(1) < rules.minFrontage)
    return SplitVerdict::NoRoadAccess;
  return SplitVerdict::Accepted;
}

}  // namespace

SplitVerdict checkSplit(const Polygon& parent, const Polygon& a, const Polygon& b, const SplitRules& rules,
                        const RoadFrontage& frontage) {
  return checkSplit(area(parent), aspectOf(parent), a, b, rules, frontage);
}

SplitVerdict checkSplit(double parentArea, double parentAspect, const Polygon& a, const Polygon& b,
                        const SplitRules& rules, const RoadFrontage& frontage) {
  std::array<double, 2> areas{}, aspects{};
  return checkChildren(
      parentArea, parentAspect, a, b, rules, [&](int k) { return frontage.longest(k == 0 ? a : b); }, areas,
      aspects);
}

SubdivisionParcel::SubdivisionParcel(Polygon p) : polygon(std::move(p)), area(urbanvec::area(polygon)) {}

namespace {

/// The SplitIndex terms of the edge p-q (absolute coordinates) about `origin`.
SplitIndex::Sums edgeTerms(const Vec2& p, const Vec2& q, const Vec2& origin) {
  const Vec2 a = p - origin, b = q - origin;
  const double c = a.x * b.y - a.y * b.x;
  SplitIndex::Sums t;
  t.c = c;
  t.mx = (a.x + b.x) * c;
  t.my = (a.y + b.y) * c;
  t.ixx = (a.x * a.x + a.x * b.x + b.x * b.x) * c;
  t.iyy = (a.y * a.y + a.y * b.y + b.y * b.y) * c;
  t.ixy = (a.x * b.y + 2.0 * a.x * a.y + 2.0 * b.x * b.y + b.x * a.y) * c;
  t.productsLocal = std::fabs(a.x * b.y) + std::fabs(a.y * b.x);
  t.crossLocal = std::fabs(c);
  t.products = std::fabs(p.x * q.y) + std::fabs(p.y * q.x);
  t.cross = std::fabs(p.x * q.y - p.y * q.x);
  return t;
}

/// The fields of SplitIndex::Sums, combined field by field.
constexpr double SplitIndex::Sums::*kSumsFields[] = {&SplitIndex::Sums::c,
                                                     &SplitIndex::Sums::mx,
                                                     &SplitIndex::Sums::my,
                                                     &SplitIndex::Sums::ixx,
                                                     &SplitIndex::Sums::iyy,
                                                     &SplitIndex::Sums::ixy,
                                                     &SplitIndex::Sums::productsLocal,
                                                     &SplitIndex::Sums::crossLocal,
                                                     &SplitIndex::Sums::products,
                                                     &SplitIndex::Sums::cross};

SplitIndex::Sums operator+(SplitIndex::Sums a, const SplitIndex::Sums& b) {
  for (const auto field : kSumsFields) a.*field += b.*field;
  return a;
}

SplitIndex::Sums operator-(SplitIndex::Sums a, const SplitIndex::Sums& b) {
  for (const auto field : kSumsFields) a.*field -= b.*field;
  return a;
}

constexpr std::uint32_t kRunEdges = 8;  ///< edges per run of SplitIndex

}  // namespace

SplitIndex buildSplitIndex(const Polygon& polygon) {
  SplitIndex index;
  buildSplitIndex(polygon, index);
  return index;
}

void buildSplitIndex(const Polygon& polygon, SplitIndex& index) {
  index.built = true;
  index.origin = Vec2{};
  index.maxAbs = index.maxLocal = index.diagonal = 0.0;
  index.runs.clear();
  index.ringRuns.assign(1, 0);
  index.prefix.clear();
  double minX = 1e300, minY = 1e300, maxX = -1e300, maxY = -1e300;
  auto extend = [&](const Ring& ring) {
    for (const Vec2& p : ring) {
      minX = std::min(minX, p.x);
      minY = std::min(minY, p.y);
      maxX = std::max(maxX, p.x);
      maxY = std::max(maxY, p.y);
    }
  };
  extend(polygon.outer);
  for (const Ring& h : polygon.holes) extend(h);
  if (minX > maxX) return;
  index.origin = {0.5 * (minX + maxX), 0.5 * (minY + maxY)};
  index.maxAbs = std::max({std::fabs(minX), std::fabs(maxX), std::fabs(minY), std::fabs(maxY)});
  index.maxLocal = std::max(maxX - index.origin.x, maxY - index.origin.y) * (1.0 + 1e-12);
  index.diagonal = std::hypot(maxX - minX, maxY - minY);
  size_t vertices = polygon.outer.size();
  for (const Ring& h : polygon.holes) vertices += h.size();
  index.runs.reserve(vertices / kRunEdges + 1 + polygon.holes.size());
  auto addRuns = [&](const Ring& ring) {
    const std::uint32_t n = ring.size() < 2 ? 0 : static_cast<std::uint32_t>(ring.size() - 1);
    for (std::uint32_t first = 0; first < n; first += kRunEdges) {
      SplitIndex::Run run;
      run.first = first;
      run.last = std::min(n, first + kRunEdges);
      double x0 = ring[first].x, x1 = x0, y0 = ring[first].y, y1 = y0;
      for (std::uint32_t i = first; i < run.last; ++i) {
        const Vec2& p = ring[i + 1];
        x0 = std::min(x0, p.x);
        x1 = std::max(x1, p.x);
        y0 = std::min(y0, p.y);
        y1 = std::max(y1, p.y);
        run.longestEdge = std::max(run.longestEdge, distance(ring[i], p));
      }
      run.centre = {0.5 * (x0 + x1), 0.5 * (y0 + y1)};
      run.half = {0.5 * (x1 - x0), 0.5 * (y1 - y0)};
      index.runs.push_back(run);
    }
    index.ringRuns.push_back(static_cast<std::uint32_t>(index.runs.size()));
  };
  addRuns(polygon.outer);
  for (const Ring& h : polygon.holes) addRuns(h);
  const Ring& outer = polygon.outer;
  index.prefix.reserve(outer.size());
  index.prefix.emplace_back();
  for (size_t i = 0; i + 1 < outer.size(); ++i)
    index.prefix.push_back(index.prefix.back() + edgeTerms(outer[i], outer[i + 1], index.origin));
}

void prepare(SubdivisionParcel& parcel, const RegularSubdivisionOptions& options,
             const RoadFrontage& frontage, const geos::Context& geos) {
  parcel.prepared = true;
  if (!parcel.aspectKnown) parcel.aspect = aspectOf(parcel.polygon);
  parcel.aspectKnown = true;
  // GEOS's TopologyPreservingSimplifier rules in plain code (core/topology_simplify.hpp): the same
  // copy without a GEOS geometry and two quadtrees per parcel (issue 21).
  thread_local Polygon copy;  // its rings' memory serves the next parcel
  const Polygon* simplified = &parcel.polygon;
  if (options.simplifyTolerance > 0.0) {
    simplifyPreservingTopology(parcel.polygon, options.simplifyTolerance, copy);
    if (area(copy) > 0.0) simplified = &copy;
  }
  // An edge of the simplified copy faces the road when it runs along road-facing lines, i.e. its
  // quarter points all lie within the simplification tolerance of them.
  const double near = options.simplifyTolerance + options.frontageTolerance;
  parcel.roadEdges.clear();
  auto scanRing = [&](const Ring& ring) {
    for (size_t i = 0; i + 1 < ring.size(); ++i) {
      const Vec2 a = ring[i], b = ring[i + 1];
      if (distance(a, b) <= 1e-9) continue;
      bool facing = true;
      for (double t : {0.25, 0.5, 0.75})
        if (!frontage.within(a + (b - a) * t, near)) {
          facing = false;
          break;
        }
      if (facing) parcel.roadEdges.push_back({a, b});
    }
  };
  scanRing(simplified->outer);
  for (const Ring& h : simplified->holes) scanRing(h);
  (void)geos;  // the simplification no longer needs GEOS
  buildSplitIndex(parcel.polygon, parcel.index);
  // The E1 parcels, which every try starts from, measure their edges' road frontage here once; a
  // parcel cut from another inherits its parent's entries.
  if (parcel.cover.empty()) {
    parcel.cover.resize(1 + parcel.polygon.holes.size());
    frontage.coverRing(parcel.polygon.outer, parcel.cover[0]);
    for (size_t h = 0; h < parcel.polygon.holes.size(); ++h)
      frontage.coverRing(parcel.polygon.holes[h], parcel.cover[h + 1]);
  }
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

/// Where the line crosses a ring: at `point`, `s` along the line, on edge `edge` of ring `ring`.
struct Crossing {
  double s;
  size_t ring;  ///< 0 for the outer ring, h + 1 for hole h
  size_t edge;
  Vec2 point;
};

/// Which ring of the parent each ring of a child comes from: an arc of ring `ring` closed by the cut
/// (walked from crossing a to b, or from b to a), a copy of it, or something else (reversed).
struct RingSource {
  enum class Kind { ArcFromA, ArcFromB, Copy, Fresh } kind;
  size_t ring;
};

/// How a cut made its two children, so their rings' road frontage entries can be inherited.
struct CutRecipe {
  Crossing a, b;
  std::array<std::vector<RingSource>, 2> rings;  ///< per child: outer ring, then holes
};

/// The piece of the line q + s·dir inside the polygon nearest q, as crossings a and b of its rings.
/// Runs of edges whose bounding box lies clearly on one side of the line are skipped: their edges,
/// with both ends farther than 1e-6 cells from the line on one side, pass none of the tests below
/// (such an edge is no crossing, not along the line and not through a vertex at the thresholds
/// used), so the crossings are those a scan of every edge finds, in the same order. Degenerate cases
/// are left to GEOS: the line through a vertex or along an edge of any ring.
/// How clearly findCut's piece is GEOS's (splitAlong's fallback): how much nearer q it is than the next
/// nearest piece, and how far along the line the nearest other crossing lies from its ends, cells.
struct CutClearance {
  double pieceGap = 1e300;
  double endGap = 1e300;
};

LineSplit findCut(const Polygon& polygon, const SplitIndex& index, const Vec2& q, const Vec2& dir,
                  Crossing& a, Crossing& b, CutClearance* clearance = nullptr) {
  thread_local std::vector<Crossing> crossings;  // reused: one split test per try and parcel
  crossings.clear();
  const double spreadX = std::fabs(dir.y), spreadY = std::fabs(dir.x);
  const double qSize = std::fabs(q.x) + std::fabs(q.y);
  auto addCrossings = [&](const Ring& ring, size_t ringIndex) {
    for (std::uint32_t r = index.ringRuns[ringIndex]; r < index.ringRuns[ringIndex + 1]; ++r) {
      const SplitIndex::Run& run = index.runs[r];
      const double centreSide = cross(run.centre - q, dir);
      const double reach = run.half.x * spreadX + run.half.y * spreadY;
      const double margin = 1e-6 + 1e-9 * run.longestEdge +
                            1e-13 * (std::fabs(run.centre.x) + std::fabs(run.centre.y) + qSize + reach);
      if (centreSide - reach > margin || centreSide + reach < -margin) continue;
      double next = cross(ring[run.first] - q, dir);
      for (size_t i = run.first; i < run.last; ++i) {
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
  if (clearance) {
    *clearance = CutClearance{};
    for (size_t k = 0; k + 1 < crossings.size(); k += 2) {
      if (k == pick) continue;
      const double lo = crossings[k].s, hi = crossings[k + 1].s;
      const double d = (lo <= 0.0 && hi >= 0.0) ? 0.0 : std::min(std::fabs(lo), std::fabs(hi));
      clearance->pieceGap = std::min(clearance->pieceGap, d - best);
    }
    if (pick > 0) clearance->endGap = crossings[pick].s - crossings[pick - 1].s;
    if (pick + 2 < crossings.size())
      clearance->endGap = std::min(clearance->endGap, crossings[pick + 2].s - crossings[pick + 1].s);
  }
  a = crossings[pick];
  b = crossings[pick + 1];
  if (a.ring != b.ring) return LineSplit::NoSplit;
  return LineSplit::Split;
}

/// Splits a polygon along the piece a-b of a line (findCut), when that piece runs from the outer ring
/// to the outer ring (each hole goes to the side that contains it) or from a hole back to the same
/// hole (it cuts off the pocket of parcel in a bay of the hole). Degenerate, left to GEOS: a hole
/// whose side is unclear because it touches a ring of the cut.
LineSplit cutPolygon(const Polygon& polygon, const Crossing& a, const Crossing& b,
                     std::array<Polygon, 2>& out, CutRecipe& recipe) {
  recipe.a = a;
  recipe.b = b;
  recipe.rings[0].clear();
  recipe.rings[1].clear();
  const Ring& ring = a.ring == 0 ? polygon.outer : polygon.holes[a.ring - 1];
  const size_t n = ring.size() - 1;
  auto walk = [&](const Crossing& from, const Crossing& to, Ring& r) {
    r.clear();
    r.reserve(n + 3);
    r.push_back(from.point);
    for (size_t i = (from.edge + 1) % n;; i = (i + 1) % n) {
      r.push_back(ring[i]);
      if (i == to.edge) break;
    }
    r.push_back(to.point);
    r.push_back(from.point);
  };
  using Kind = RingSource::Kind;
  if (a.ring != 0) {
    // The piece runs from a hole back to the same hole across the mouth of a bay of it: the chord
    // and the arc of the hole around the bay close the pocket of parcel in the bay (the smaller of the
    // two rings: the other one also holds the hole), and the rest of the parcel gets the hole grown by
    // that pocket. The other holes go to the side that contains them.
    Ring first, second;
    walk(a, b, first);
    walk(b, a, second);
    const bool firstIsPocket = std::fabs(signedArea(first)) < std::fabs(signedArea(second));
    Ring& pocket = firstIsPocket ? first : second;
    Ring& grown = firstIsPocket ? second : first;
    const bool outerPositive = signedArea(polygon.outer) > 0.0, holePositive = signedArea(ring) > 0.0;
    const Kind pocketArc = firstIsPocket ? Kind::ArcFromA : Kind::ArcFromB;
    const Kind grownArc = firstIsPocket ? Kind::ArcFromB : Kind::ArcFromA;
    bool pocketReversed = false, grownReversed = false;
    if ((signedArea(pocket) > 0.0) != outerPositive) {
      std::reverse(pocket.begin(), pocket.end());
      pocketReversed = true;
    }
    if ((signedArea(grown) > 0.0) != holePositive) {
      std::reverse(grown.begin(), grown.end());
      grownReversed = true;
    }
    out[0] = Polygon{std::move(pocket), {}};
    out[1] = Polygon{polygon.outer, {std::move(grown)}};
    recipe.rings[0].push_back({pocketReversed ? Kind::Fresh : pocketArc, a.ring});
    recipe.rings[1].push_back({Kind::Copy, 0});
    recipe.rings[1].push_back({grownReversed ? Kind::Fresh : grownArc, a.ring});
    for (size_t h = 0; h < polygon.holes.size(); ++h) {
      if (h + 1 == a.ring) continue;
      const Ring& hole = polygon.holes[h];
      const bool inFirst = insideRing(hole[0], out[0].outer), inSecond = insideRing(hole[1], out[0].outer);
      if (inFirst != inSecond) return LineSplit::Degenerate;
      out[inFirst ? 0 : 1].holes.push_back(hole);
      recipe.rings[inFirst ? 0 : 1].push_back({Kind::Copy, h + 1});
    }
    return LineSplit::Split;
  }
  out[0].holes.clear();
  out[1].holes.clear();
  walk(a, b, out[0].outer);
  walk(b, a, out[1].outer);
  recipe.rings[0].push_back({Kind::ArcFromA, 0});
  recipe.rings[1].push_back({Kind::ArcFromB, 0});
  // The chord meets no hole, so each hole lies wholly on one side. A valid hole touches the outer ring
  // in at most one point, so two of its vertices agree on the side unless one lies on that point.
  for (size_t h = 0; h < polygon.holes.size(); ++h) {
    const Ring& hole = polygon.holes[h];
    const bool first = insideRing(hole[0], out[0].outer), second = insideRing(hole[1], out[0].outer);
    if (first != second) return LineSplit::Degenerate;
    out[first ? 0 : 1].holes.push_back(hole);
    recipe.rings[first ? 0 : 1].push_back({Kind::Copy, h + 1});
  }
  return LineSplit::Split;
}

/// The road frontage entries of child k's rings from its parent's and the cut.
void childCover(const SubdivisionParcel& parent, const Polygon& child, const CutRecipe& recipe, int k,
                const RoadFrontage& frontage, std::vector<RoadFrontage::RingCover>& cover) {
  const std::vector<RingSource>& sources = recipe.rings[static_cast<size_t>(k)];
  cover.resize(sources.size());
  for (size_t j = 0; j < sources.size(); ++j) {
    const RingSource& source = sources[j];
    const Ring& ring = j == 0 ? child.outer : child.holes[j - 1];
    RoadFrontage::RingCover& c = cover[j];
    switch (source.kind) {
      case RingSource::Kind::Copy:
        c = parent.cover[source.ring];
        break;
      case RingSource::Kind::Fresh:
        frontage.coverRing(ring, c);
        break;
      case RingSource::Kind::ArcFromA:
      case RingSource::Kind::ArcFromB: {
        // The ring is walk(from, to): from, parent vertices from.edge + 1 .. to.edge, to, from. Its
        // edges between parent vertices are the parent's edges from.edge + 1 .. to.edge - 1.
        const bool fromA = source.kind == RingSource::Kind::ArcFromA;
        const Crossing& from = fromA ? recipe.a : recipe.b;
        const Crossing& to = fromA ? recipe.b : recipe.a;
        const RoadFrontage::RingCover& p = parent.cover[source.ring];
        const size_t n = p.edges();
        c.clear();
        frontage.coverEdge(ring[0], ring[1], c);
        const size_t first = (from.edge + 1) % n, count = (to.edge + n - from.edge - 1) % n;
        const size_t head = std::min(count, n - first);
        RoadFrontage::copyEdges(p, first, head, c);
        RoadFrontage::copyEdges(p, 0, count - head, c);
        const size_t m = ring.size();
        frontage.coverEdge(ring[m - 3], ring[m - 2], c);
        frontage.coverEdge(ring[m - 2], ring[m - 1], c);
        break;
      }
    }
  }
}

/// The longest road frontage of a polygon from its rings' entries, as RoadFrontage::longest().
double longestOfCovers(const std::vector<RoadFrontage::RingCover>& cover, const RoadFrontage& frontage) {
  double best = frontage.longestOfCover(cover[0]);
  for (size_t j = 1; j < cover.size(); ++j) best = std::max(best, frontage.longestOfCover(cover[j]));
  return best;
}

/// Area, centroid and central second moments of the child walk(from, to) of the outer ring from the
/// parcel's SplitIndex, with bounds on how far the exact computation on the child's ring (absolute
/// coordinates, checkChildren) can lie from them.
struct ChildEstimate {
  double area = 0.0;
  double areaMargin = 0.0;    ///< bound on |area - exact area|, cells²
  double momentMargin = 0.0;  ///< bound on the difference of each central second moment, cells²
  Vec2 centroid;              ///< local coordinates
  double sxx = 0.0, syy = 0.0, sxy = 0.0;
  size_t edges = 0;
};

ChildEstimate estimateChild(const SubdivisionParcel& parcel, const Crossing& from, const Crossing& to) {
  const SplitIndex& index = parcel.index;
  const Ring& ring = parcel.polygon.outer;
  const size_t n = ring.size() - 1;
  const size_t first = (from.edge + 1) % n;
  const size_t count = (to.edge + n - from.edge - 1) % n;  // parent edges first .. to.edge - 1
  const auto& prefix = index.prefix;
  SplitIndex::Sums sums = first + count <= n ? prefix[first + count] - prefix[first]
                                             : (prefix[n] - prefix[first]) + prefix[first + count - n];
  sums = sums + edgeTerms(from.point, ring[first], index.origin) +
         edgeTerms(ring[to.edge], to.point, index.origin) + edgeTerms(to.point, from.point, index.origin);
  ChildEstimate e;
  e.edges = count + 3;
  const double unit = 1.12e-16;  // unit roundoff, rounded up
  const double m = static_cast<double>(e.edges), whole = static_cast<double>(n);
  // Bounds on the rounding of checkChildren's sums over the child's ring in absolute coordinates and
  // of the prefix differences here (local coordinates, sums over up to 2n + 3 terms). A cross product
  // p × q errs by at most u (|px qy| + |py qx| + |p × q|) (u the unit roundoff); a sum of k terms by
  // k u times the sum of their magnitudes. Both doubled for safety.
  const SplitIndex::Sums& ringSums = prefix[n];
  const double products = sums.products, crosses = sums.cross;
  const double productsLocal = ringSums.productsLocal + sums.productsLocal,
               crossesLocal = ringSums.crossLocal + sums.crossLocal;
  const double twiceAreaError = 2.0 * unit * (products + (m + 2.0) * crosses) +
                                2.0 * unit * (productsLocal + (2.0 * whole + 6.0) * crossesLocal);
  e.area = 0.5 * std::fabs(sums.c);
  e.areaMargin = 0.5 * twiceAreaError + 1e-300;
  if (!(e.area > 16.0 * e.areaMargin)) return e;
  const double orientation = sums.c >= 0.0 ? 1.0 : -1.0;
  const double a = e.area;
  e.centroid = {orientation * sums.mx / 6.0 / a, orientation * sums.my / 6.0 / a};
  e.sxx = orientation * sums.ixx / 12.0 / a - e.centroid.x * e.centroid.x;
  e.syy = orientation * sums.iyy / 12.0 / a - e.centroid.y * e.centroid.y;
  e.sxy = orientation * sums.ixy / 24.0 / a - e.centroid.x * e.centroid.y;
  // A central second moment (e.g. Σ(x² + x x' + x'²) c / 12a - cx², c the edges' cross products)
  // computed in coordinates up to X from the origin: the rounding of its k-term sums and of the
  // area it divides by errs by at most about (2k + 6) u X² Σ|c| / a plus 4 u X²; the rounding of
  // each c moves it by at most 2 D² u (|px qy| + |py qx| + |c|) / a, D the largest distance of a
  // vertex from the centroid (the moment depends on c only through coordinates about the centroid).
  // Doubled for safety, for checkChildren's absolute and this function's local coordinates.
  const double big = index.maxAbs * (1.0 + 1e-12), local = index.maxLocal, reach = index.diagonal;
  auto momentError = [&](double coordinate, double terms, double sumCross, double sumProducts) {
    return 2.0 * unit *
           ((2.0 * terms + 6.0) * coordinate * coordinate * sumCross / a + 4.0 * coordinate * coordinate +
            2.0 * reach * reach * (sumProducts + sumCross) / a);
  };
  e.momentMargin = momentError(big, m, crosses, products) +
                   momentError(local, 2.0 * whole + 3.0, crossesLocal, productsLocal);
  return e;
}

/// The PCA aspect of child walk(from, to) from its estimate, as orientedBox() computes it, and a bound
/// on its difference from orientedBox's value; a negative bound when no useful bound exists (near-round
/// moments, whose axis the rounding could turn anywhere).
double estimateAspect(const SubdivisionParcel& parcel, const Crossing& from, const Crossing& to,
                      const ChildEstimate& e, double& bound) {
  bound = -1.0;
  const double delta = e.momentMargin;
  const double cos2 = e.sxx - e.syy, sin2 = 2.0 * e.sxy;
  const double radius = std::sqrt(cos2 * cos2 + sin2 * sin2);
  if (!(radius > 8.0 * delta)) return 0.0;
  Vec2 u;
  if (cos2 >= 0.0) {
    u.x = std::sqrt(0.5 * (1.0 + cos2 / radius));
    u.y = sin2 / (2.0 * radius * u.x);
  } else {
    u.y = std::copysign(std::sqrt(0.5 * (1.0 - cos2 / radius)), sin2);
    u.x = sin2 / (2.0 * radius * u.y);
  }
  const Vec2 v{-u.y, u.x};
  const SplitIndex& index = parcel.index;
  const Ring& ring = parcel.polygon.outer;
  const size_t n = ring.size() - 1;
  // The extents along u and v, from the vertices about the local origin (the centroid only shifts
  // both ends of an extent).
  // Two sets of running extents, for two vertices at a time (shorter dependency chains).
  std::array<double, 2> minU{1e300, 1e300}, maxU{-1e300, -1e300}, minV{1e300, 1e300}, maxV{-1e300, -1e300};
  const Vec2 origin = index.origin;
  auto project = [&](const Vec2& p, size_t k) {
    const Vec2 d = p - origin;
    const double du = dot(d, u), dv = dot(d, v);
    minU[k] = std::min(minU[k], du);
    maxU[k] = std::max(maxU[k], du);
    minV[k] = std::min(minV[k], dv);
    maxV[k] = std::max(maxV[k], dv);
  };
  auto projectRange = [&](size_t begin, size_t end) {
    size_t i = begin;
    for (; i + 1 < end; i += 2) {
      project(ring[i], 0);
      project(ring[i + 1], 1);
    }
    if (i < end) project(ring[i], 0);
  };
  project(from.point, 0);
  project(to.point, 1);
  const size_t first = (from.edge + 1) % n;
  if (first <= to.edge) {
    projectRange(first, to.edge + 1);
  } else {
    projectRange(first, n);
    projectRange(0, to.edge + 1);
  }
  const double eu = std::max(maxU[0], maxU[1]) - std::min(minU[0], minU[1]),
               ev = std::max(maxV[0], maxV[1]) - std::min(minV[0], minV[1]);
  const double longSide = std::max(eu, ev), shortSide = std::min(eu, ev);
  // The moments' difference turns the axis by at most about 1.5 δ / radius (the half angle of a
  // vector of length radius moved by 2√2 δ); each extent then moves by at most twice the diameter
  // times that angle, plus the rounding of the projections.
  const double unit = 1.12e-16, reach = index.diagonal;
  const double turn = 4.0 * delta / (radius - 3.0 * delta) + 1e-13;
  const double extentError = 2.0 * reach * turn + 32.0 * unit * (index.maxAbs + reach);
  if (!(longSide > 4.0 * extentError)) return 0.0;
  bound = 4.0 * extentError / longSide + 1e-12;
  return shortSide / longSide;
}

/// The verdict of checkChildren on the outer-to-outer cut a-b of a parcel without holes when the
/// estimates make it certain to be a rejection for size, rectangularity or residential variation;
/// nothing otherwise (then the children are built and checked exactly).
std::optional<SplitVerdict> screenCut(const SubdivisionParcel& parcel, const Crossing& a, const Crossing& b,
                                      const SplitRules& rules) {
  const ChildEstimate first = estimateChild(parcel, a, b), second = estimateChild(parcel, b, a);
  auto surelyBelow = [](const ChildEstimate& e, double limit) { return e.area + e.areaMargin < limit; };
  auto surelyAtLeast = [](const ChildEstimate& e, double limit) { return e.area - e.areaMargin >= limit; };
  // Size: area < minArea or area <= 0.
  for (const ChildEstimate* e : {&first, &second})
    if (surelyBelow(*e, rules.minArea) || e->area + e->areaMargin <= 0.0) return SplitVerdict::TooSmall;
  for (const ChildEstimate* e : {&first, &second})
    if (!surelyAtLeast(*e, rules.minArea) || !(e->area - e->areaMargin > 0.0)) return std::nullopt;
  // Rectangularity against the threshold (or the parent's aspect), strictly when the parent is below it.
  const double parentAspect = parcel.aspect;
  const bool strict = !(parentAspect >= rules.aspectThreshold);
  const double limit = rules.compareParentAspect || strict ? parentAspect : rules.aspectThreshold;
  bool surePass = true;
  for (const auto& [from, to, e] : {std::tuple{&a, &b, &first}, std::tuple{&b, &a, &second}}) {
    double bound = -1.0;
    const double aspect = estimateAspect(parcel, *from, *to, *e, bound);
    if (bound < 0.0) {
      surePass = false;
      continue;
    }
    if (aspect + bound < limit) return SplitVerdict::TooRectangular;
    if (!(aspect - bound > limit)) surePass = false;
  }
  if (!surePass) return std::nullopt;
  if (rules.residentialRule) {
    const double least = rules.minChildShare * parcel.area;
    if (surelyBelow(first, least) || surelyBelow(second, least)) return SplitVerdict::UnequalResidential;
    if (!surelyAtLeast(first, least) || !surelyAtLeast(second, least)) return std::nullopt;
  }
  return std::nullopt;
}

/// The verdict splitAlong's GEOS fallback gives a cut a-b from the outer ring to the outer ring that
/// cutPolygon left to it because a hole touches the outer ring at its first or second vertex (the one
/// case of the fallback on real blocks, issue 21), when it is certainly a rejection for size,
/// rectangularity or residential variation; nothing otherwise. The children are cutPolygon's outer
/// rings with each hole on the side of its vertices off the parent's outer ring. GEOS's faces are the
/// same regions with their cut points within 1e-9 cells (its noding, or its snap rounding on a 1e-9
/// grid) and other rings' start and order, so the areas and PCA moments are compared with bounds on
/// that and on the rounding of both computations (as screenCut's); a piece GEOS could choose
/// differently, an overshoot that could meet another edge, or a child near the sliver size GEOS drops
/// leaves the decision to GEOS.
std::optional<SplitVerdict> touchingHoleVerdict(const SubdivisionParcel& parcel, const Crossing& a,
                                                const Crossing& b, const CutClearance& clearance,
                                                const SplitRules& rules, std::array<Polygon, 2>& children) {
  const Polygon& polygon = parcel.polygon;
  if (a.ring != 0 || b.ring != 0 || !(clearance.pieceGap > 1e-6) || !(clearance.endGap > 1e-6) ||
      !(b.s - a.s > 1e-6))
    return std::nullopt;
  Ring& first = children[0].outer;  // cutPolygon walked both outer rings before it met the hole
  children[0].holes.clear();
  children[1].holes.clear();
  auto onOuter = [&](const Vec2& v) {
    return std::find(polygon.outer.begin(), polygon.outer.end(), v) != polygon.outer.end();
  };
  for (const Ring& hole : polygon.holes) {
    // The vertices off the outer ring lie strictly inside one child (none lies on the cut line: findCut
    // leaves such lines to GEOS); all of them, at least two, must agree.
    int inFirst = 0, votes = 0;
    for (size_t k = 0; k + 1 < hole.size(); ++k) {
      if (onOuter(hole[k])) continue;
      inFirst += insideRing(hole[k], first);
      ++votes;
    }
    if (votes < 2 || (inFirst != 0 && inFirst != votes)) return std::nullopt;
    children[inFirst ? 0 : 1].holes.push_back(hole);
  }
  const SplitIndex& index = parcel.index;
  const double unit = 1.12e-16, shift = 1e-9;  // unit roundoff (rounded up); cut points' displacement
  const double big = index.maxAbs * (1.0 + 1e-12) + index.diagonal, reach = index.diagonal;
  std::array<double, 2> areas{}, areaMargins{};
  std::array<double, 2> aspects{}, aspectBounds{};
  for (size_t k = 0; k < 2; ++k) {
    const Polygon& child = children[k];
    double area = 0.0, perimeter = 0.0, sumCross = 0.0, sumProducts = 0.0, vertices = 0.0;
    std::vector<double> ringAreas;
    auto addRing = [&](const Ring& ring, bool hole) {
      const double ringArea = signedArea(ring);
      ringAreas.push_back(ringArea);
      area += hole ? -std::fabs(ringArea) : std::fabs(ringArea);
      vertices += static_cast<double>(ring.size());
      for (size_t i = 0; i + 1 < ring.size(); ++i) {
        const Vec2& p = ring[i];
        const Vec2& q = ring[i + 1];
        perimeter += distance(p, q);
        sumCross += std::fabs(cross(p, q));
        sumProducts += std::fabs(p.x * q.y) + std::fabs(p.y * q.x);
      }
    };
    addRing(child.outer, false);
    for (const Ring& h : child.holes) addRing(h, true);
    const double terms = vertices + 8.0;
    // Either computation's rounding (a sum of `terms` cross products in coordinates up to `big`) plus
    // the area the displaced cut points and snapped vertices sweep; doubled.
    areaMargins[k] =
        2.0 * (2.0 * unit * (sumProducts + (terms + 2.0) * sumCross) + 2.0 * shift * (perimeter + reach));
    areas[k] = area;
    if (!(area > 1e-6 * parcel.area + areaMargins[k])) return std::nullopt;  // near GEOS's sliver size
    const PolygonMoments m = polygonMoments(child, ringAreas.data());
    const double delta = 2.0 * 2.0 * unit *
                             ((2.0 * terms + 6.0) * big * big * sumCross / area + 4.0 * big * big +
                              2.0 * reach * reach * (sumProducts + sumCross) / area) +
                         4.0 * shift * perimeter * reach * reach / area;
    const double cos2 = m.sxx - m.syy, sin2 = 2.0 * m.sxy;
    const double radius = std::sqrt(cos2 * cos2 + sin2 * sin2);
    aspectBounds[k] = -1.0;
    if (radius > 8.0 * delta) {
      const OrientedBox box = orientedBox(child, ringAreas.data());
      const double turn = 4.0 * delta / (radius - 3.0 * delta) + 1e-13;
      const double extentError = 2.0 * reach * turn + 32.0 * unit * (big + reach) + 4.0 * shift;
      if (box.length > 4.0 * extentError) {
        aspects[k] = box.aspect();
        aspectBounds[k] = 4.0 * extentError / box.length + 1e-12;
      }
    }
  }
  // checkChildren's order: size, rectangularity, residential variation (road access is left to GEOS).
  for (size_t k = 0; k < 2; ++k)
    if (areas[k] + areaMargins[k] < rules.minArea) return SplitVerdict::TooSmall;
  for (size_t k = 0; k < 2; ++k)
    if (!(areas[k] - areaMargins[k] >= rules.minArea)) return std::nullopt;
  const double parentAspect = parcel.aspect;
  const bool strict = !(parentAspect >= rules.aspectThreshold);
  const double limit = rules.compareParentAspect || strict ? parentAspect : rules.aspectThreshold;
  bool surePass = true;
  for (size_t k = 0; k < 2; ++k) {
    if (aspectBounds[k] < 0.0) {
      surePass = false;
      continue;
    }
    if (aspects[k] + aspectBounds[k] < limit) return SplitVerdict::TooRectangular;
    if (!(aspects[k] - aspectBounds[k] > limit)) surePass = false;
  }
  if (!surePass || !rules.residentialRule) return std::nullopt;
  const double least = rules.minChildShare * parcel.area;
  for (size_t k = 0; k < 2; ++k)
    if (areas[k] + areaMargins[k] < least) return SplitVerdict::UnequalResidential;
  return std::nullopt;
}

/// Resets a child slot for a new polygon whose area and aspect are known; `polygon` gets the slot's
/// old polygon, so its memory serves the next cut.
void setChild(SubdivisionParcel& child, Polygon& polygon, double area, double aspect, bool aspectKnown) {
  std::swap(child.polygon, polygon);
  child.area = area;
  child.aspect = aspect;
  child.aspectKnown = aspectKnown;
  child.prepared = false;
  child.roadEdges.clear();
  child.index.built = false;
}

}  // namespace

SplitVerdict splitAlong(SubdivisionParcel& parcel, const Vec2& q, const Vec2& dir, const SplitRules& rules,
                        const RoadFrontage& frontage, const geos::Context& geos,
                        std::array<SubdivisionParcel, 2>& out, bool screen) {
  if (!parcel.index.built) buildSplitIndex(parcel.polygon, parcel.index);
  if (!parcel.aspectKnown) {
    parcel.aspect = aspectOf(parcel.polygon);
    parcel.aspectKnown = true;
  }
  if (parcel.cover.empty()) {
    parcel.cover.resize(1 + parcel.polygon.holes.size());
    frontage.coverRing(parcel.polygon.outer, parcel.cover[0]);
    for (size_t h = 0; h < parcel.polygon.holes.size(); ++h)
      frontage.coverRing(parcel.polygon.holes[h], parcel.cover[h + 1]);
  }
  // Transfer to the original: the piece of the perpendicular line inside the original parcel that is
  // nearest the sampled point (Q18). Plain code, GEOS in the degenerate cases.
  if (parcel.polygon.outer.size() >= 4) {
    Crossing a{}, b{};
    CutClearance clearance;
    const LineSplit cut = findCut(parcel.polygon, parcel.index, q, dir, a, b, &clearance);
    if (cut == LineSplit::NoSplit) return SplitVerdict::BadGeometry;
    if (cut == LineSplit::Split) {
      if (screen && a.ring == 0 && parcel.polygon.holes.empty())
        if (const std::optional<SplitVerdict> verdict = screenCut(parcel, a, b, rules)) return *verdict;
      thread_local std::array<Polygon, 2> children;
      thread_local CutRecipe recipe;
      if (cutPolygon(parcel.polygon, a, b, children, recipe) == LineSplit::Split) {
        std::array<double, 2> areas{}, aspects{};
        auto frontageOf = [&](int k) {
          std::vector<RoadFrontage::RingCover>& cover = out[static_cast<size_t>(k)].cover;
          childCover(parcel, children[static_cast<size_t>(k)], recipe, k, frontage, cover);
          return longestOfCovers(cover, frontage);
        };
        const SplitVerdict verdict = checkChildren(parcel.area, parcel.aspect, children[0], children[1],
                                                   rules, frontageOf, areas, aspects);
        if (verdict == SplitVerdict::Accepted)
          for (size_t k = 0; k < 2; ++k) setChild(out[k], children[k], areas[k], aspects[k], true);
        return verdict;
      }
      if (screen)
        if (const std::optional<SplitVerdict> verdict =
                touchingHoleVerdict(parcel, a, b, clearance, rules, children))
          return *verdict;
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
  geos::GeomPtr line = geos.lineString({q - dir * reach, q + dir * reach});
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
  const Vec2 along = (e - s) / distance(s, e);
  const MultiLineString cutLine{{s - along * kOvershoot, e + along * kOvershoot}};
  MultiPolygon faces = facesInside(geos, polygon.get(), cutLine);
  if (faces.size() != 2) return SplitVerdict::BadGeometry;
  const SplitVerdict verdict = checkSplit(parcel.area, parcel.aspect, faces[0], faces[1], rules, frontage);
  if (verdict == SplitVerdict::Accepted) {
    for (size_t k = 0; k < 2; ++k) {
      const double faceArea = urbanvec::area(faces[k]);
      setChild(out[k], faces[k], faceArea, 1.0, false);
      out[k].cover.clear();
    }
  }
  return verdict;
}

SplitVerdict trySplit(SubdivisionParcel& parcel, const SplitRules& rules,
                      const RegularSubdivisionOptions& options, const RoadFrontage& frontage,
                      const geos::Context& geos, Rng& rng, std::array<SubdivisionParcel, 2>& out) {
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
  NormalDraw position(0.5, options.positionSigma);  // std::normal_distribution's draws, cheaper
  double t = position(rng);
  for (int i = 0; i < 64 && (t <= 0.0 || t >= 1.0); ++i) t = position(rng);
  if (t <= 0.0 || t >= 1.0) t = 0.5;

  const Vec2 a = parcel.roadEdges[edge][0], b = parcel.roadEdges[edge][1];
  const Vec2 q = a + (b - a) * t;
  const Vec2 along = (b - a) / distance(a, b);
  const Vec2 normal{-along.y, along.x};
  return splitAlong(parcel, q, normal, rules, frontage, geos, out);
}

SplitVerdict trySplit(SubdivisionParcel& parcel, const SplitRules& rules,
                      const RegularSubdivisionOptions& options, const RoadFrontage& frontage,
                      const geos::Context& geos, Rng& rng, std::array<Polygon, 2>& out) {
  std::array<SubdivisionParcel, 2> children;
  const SplitVerdict verdict = trySplit(parcel, rules, options, frontage, geos, rng, children);
  if (verdict == SplitVerdict::Accepted)
    for (size_t k = 0; k < 2; ++k) out[k] = std::move(children[k].polygon);
  return verdict;
}

bool subdivide(std::vector<SubdivisionParcel>& parcels, int target, const SplitRules& rules,
               const RegularSubdivisionOptions& options, const RoadFrontage& frontage,
               const geos::Context& geos, Rng& rng, SplitStats& stats) {
  SubdivisionScratch scratch;
  return subdivide(parcels, target, rules, options, frontage, geos, rng, stats, scratch);
}

bool subdivide(std::vector<SubdivisionParcel>& parcels, int target, const SplitRules& rules,
               const RegularSubdivisionOptions& options, const RoadFrontage& frontage,
               const geos::Context& geos, Rng& rng, SplitStats& stats, SubdivisionScratch& scratch) {
  std::array<SubdivisionParcel, 2>& children = scratch.children;  // reused by every attempt
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
      const SplitVerdict verdict = trySplit(parcels[index], rules, options, frontage, geos, rng, children);
      if (verdict != SplitVerdict::Accepted) {
        ++stats.rejected[static_cast<int>(verdict)];
        continue;
      }
      ++stats.accepted;
      // Swaps, not moves: the children's slots keep the replaced parcel's and a spare's lists.
      std::swap(parcels[index], children[0]);
      if (scratch.spare.empty()) {
        parcels.push_back(std::move(children[1]));
      } else {
        parcels.push_back(std::move(scratch.spare.back()));
        scratch.spare.pop_back();
        std::swap(parcels.back(), children[1]);
      }
      split = true;
    }
    if (!split) return false;
  }
  return true;
}

}  // namespace urbanvec::vectorize::parcels
