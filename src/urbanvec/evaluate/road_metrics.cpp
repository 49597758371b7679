// Road metrics of the evaluator (issue 2 §3): see road_metrics.hpp.
#include "urbanvec/evaluate/road_metrics.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <variant>

#include "urbanvec/core/error.hpp"
#include "urbanvec/core/geos.hpp"
#include "urbanvec/core/segment_contact.hpp"

namespace urbanvec::evaluate {

namespace {

constexpr double kDegreesPerRadian = 180.0 / 3.14159265358979323846;

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

double pointToSegment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = dot(ab, ab);
  if (len2 == 0.0) return distance(p, a);
  const double t = std::clamp(dot(p - a, ab) / len2, 0.0, 1.0);
  return distance(p, a + ab * t);
}

/// A segment stored in the STRtree; a query point is a segment of zero length.
struct Segment {
  Vec2 a;
  Vec2 b;
};

/// GEOS calls this with one tree item and the query item, in an order it does not promise.
int segmentDistance(const void* item1, const void* item2, double* result, void*) {
  const Segment& s = *static_cast<const Segment*>(item1);
  const Segment& t = *static_cast<const Segment*>(item2);
  if (segmentsCross(s.a, s.b, t.a, t.b)) {
    *result = 0.0;
    return 1;
  }
  *result = std::min({pointToSegment(s.a, t.a, t.b), pointToSegment(s.b, t.a, t.b),
                      pointToSegment(t.a, s.a, s.b), pointToSegment(t.b, s.a, s.b)});
  return 1;
}

struct TreeDeleter {
  GEOSContextHandle_t handle;
  void operator()(GEOSSTRtree* tree) const { GEOSSTRtree_destroy_r(handle, tree); }
};

}  // namespace

std::vector<LineString> roadCentrelines(const Layer& roads, const EvaluateOptions& options,
                                        std::size_t* featureCount) {
  const int classField = roads.fieldIndex(options.roadClassField);
  std::vector<std::string> excluded;
  for (const std::string& c : options.excludedRoadClasses) excluded.push_back(lower(c));
  std::vector<LineString> lines;
  std::size_t kept = 0;
  for (const Feature& feature : roads.features) {
    if (classField >= 0) {
      const FieldValue& value = feature.values[static_cast<std::size_t>(classField)];
      if (const auto* name = std::get_if<std::string>(&value);
          name && std::find(excluded.begin(), excluded.end(), lower(*name)) != excluded.end())
        continue;
    }
    std::vector<const LineString*> parts;
    if (const auto* line = std::get_if<LineString>(&feature.geometry)) parts.push_back(line);
    if (const auto* multi = std::get_if<MultiLineString>(&feature.geometry))
      for (const LineString& l : *multi) parts.push_back(&l);
    bool any = false;
    for (const LineString* part : parts) {
      if (part->size() < 2) continue;
      lines.push_back(*part);
      any = true;
    }
    if (any) ++kept;
  }
  if (featureCount) *featureCount = kept;
  return lines;
}

std::vector<Vec2> samplePoints(const std::vector<LineString>& lines, double spacing) {
  if (!(spacing > 0.0)) throw invalidOption("the sample spacing must be positive");
  std::vector<Vec2> points;
  for (const LineString& line : lines) {
    const double total = length(line);
    if (total <= 0.0) {
      points.push_back(line.front());
      continue;
    }
    const auto pieces = std::max<std::size_t>(1, static_cast<std::size_t>(std::llround(total / spacing)));
    const double step = total / static_cast<double>(pieces);
    double target = step / 2.0;
    double walked = 0.0;
    for (std::size_t i = 1; i < line.size(); ++i) {
      const double segment = distance(line[i - 1], line[i]);
      while (target <= walked + segment && target < total) {
        const double t = segment > 0.0 ? (target - walked) / segment : 0.0;
        points.push_back(line[i - 1] + (line[i] - line[i - 1]) * t);
        target += step;
      }
      walked += segment;
    }
  }
  return points;
}

std::vector<double> nearestDistances(const std::vector<Vec2>& points, const std::vector<LineString>& lines,
                                     const Progress& progress) {
  std::vector<double> out;
  if (points.empty() || lines.empty()) return out;
  geos::Context ctx;
  const GEOSContextHandle_t h = ctx.handle();
  std::vector<Segment> segments;
  for (const LineString& line : lines)
    for (std::size_t i = 1; i < line.size(); ++i) segments.push_back({line[i - 1], line[i]});
  // The envelopes must outlive the tree: GEOS reads them while building it on the first query.
  std::vector<geos::GeomPtr> envelopes;
  envelopes.reserve(segments.size());
  std::unique_ptr<GEOSSTRtree, TreeDeleter> tree(GEOSSTRtree_create_r(h, 10), TreeDeleter{h});
  if (!tree) throw internalError("GEOS could not create an STRtree: " + ctx.lastError());
  for (Segment& s : segments) {
    envelopes.push_back(s.a == s.b ? ctx.point(s.a) : ctx.lineString({s.a, s.b}));
    GEOSSTRtree_insert_r(h, tree.get(), envelopes.back().get(), &s);
  }
  ProgressTicker ticker(progress, "road distances", points.size());
  out.reserve(points.size());
  for (const Vec2& p : points) {
    Segment query{p, p};
    geos::GeomPtr where = ctx.point(p);
    const void* nearest =
        GEOSSTRtree_nearest_generic_r(h, tree.get(), &query, where.get(), segmentDistance, nullptr);
    if (!nearest) throw internalError("GEOS found no nearest road segment: " + ctx.lastError());
    double d = 0.0;
    segmentDistance(nearest, &query, &d, nullptr);
    out.push_back(d);
    ticker.tick();
  }
  ticker.finish();
  return out;
}

double quantile(std::vector<double> values, double q) {
  if (values.empty()) throw internalError("quantile of no values");
  std::sort(values.begin(), values.end());
  const double position = std::clamp(q, 0.0, 1.0) * static_cast<double>(values.size() - 1);
  const auto below = static_cast<std::size_t>(std::floor(position));
  const std::size_t above = std::min(below + 1, values.size() - 1);
  const double t = position - static_cast<double>(below);
  return values[below] + (values[above] - values[below]) * t;
}

DistanceSummary summariseDistances(const std::vector<double>& distances, double cellSize) {
  DistanceSummary s;
  s.samples = distances.size();
  s.medianMetres = quantile(distances, 0.5);
  s.p95Metres = quantile(distances, 0.95);
  s.medianCells = s.medianMetres / cellSize;
  s.p95Cells = s.p95Metres / cellSize;
  return s;
}

std::vector<double> vertexTurns(const LineString& line) {
  std::vector<double> turns;
  Vec2 previous;
  bool havePrevious = false;
  for (std::size_t i = 1; i < line.size(); ++i) {
    const Vec2 direction = line[i] - line[i - 1];
    if (direction.x == 0.0 && direction.y == 0.0) continue;
    if (havePrevious)
      turns.push_back(std::atan2(std::abs(cross(previous, direction)), dot(previous, direction)) *
                      kDegreesPerRadian);
    previous = direction;
    havePrevious = true;
  }
  return turns;
}

double turningDegrees(const LineString& line) {
  double total = 0.0;
  for (double t : vertexTurns(line)) total += t;
  return total;
}

std::vector<double> turningPerKmByBend(const std::vector<LineString>& lines,
                                       const std::vector<double>& edges) {
  std::vector<double> degrees(edges.size() + 1, 0.0);
  double metres = 0.0;
  for (const LineString& line : lines) {
    for (double t : vertexTurns(line))
      degrees[static_cast<std::size_t>(std::upper_bound(edges.begin(), edges.end(), t) - edges.begin())] += t;
    metres += length(line);
  }
  for (double& d : degrees) d = metres > 0.0 ? d / (metres / 1000.0) : 0.0;
  return degrees;
}

double turningPerKm(const std::vector<LineString>& lines) {
  double degrees = 0.0;
  double metres = 0.0;
  for (const LineString& line : lines) {
    degrees += turningDegrees(line);
    metres += length(line);
  }
  return metres > 0.0 ? degrees / (metres / 1000.0) : 0.0;
}

}  // namespace urbanvec::evaluate
