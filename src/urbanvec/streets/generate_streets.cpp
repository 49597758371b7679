// The streets pipeline (spec chen-streets.md §1 stages one and two, §10 graph and blocks).
#include "urbanvec/streets/generate_streets.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "urbanvec/core/error.hpp"
#include "urbanvec/core/geos.hpp"
#include "urbanvec/core/landuse.hpp"
#include "urbanvec/core/planar_graph.hpp"
#include "urbanvec/core/random.hpp"
#include "urbanvec/core/uniform_grid.hpp"
#include "urbanvec/gridify/untagged_land.hpp"
#include "urbanvec/streets/graph_noise.hpp"
#include "urbanvec/streets/polygon_index.hpp"

namespace urbanvec::streets {
namespace {

/// The level of the traced street nearest to a point (for the noded pieces, which lose it).
class LevelLookup {
 public:
  LevelLookup(const std::vector<Street>& streets, const Vec2& lo, const Vec2& hi, double cell)
      : grid_(lo, hi, cell) {
    // Every bucket of a segment's box: an existing road's segment can be far longer than a bucket.
    for (const Street& s : streets)
      for (std::size_t i = 0; i + 1 < s.line.size(); ++i)
        grid_.insert(s.line[i], s.line[i + 1], {s.line[i], s.line[i + 1], s.level});
  }
  /// The level of the nearest street within maxDistance, else Outline.
  StreetLevel at(const Vec2& p, double maxDistance) const {
    double best = std::numeric_limits<double>::infinity();
    StreetLevel level = StreetLevel::Minor;
    const double reach = grid_.cell();
    grid_.forBox(p - Vec2{reach, reach}, p + Vec2{reach, reach}, [&](const std::vector<Seg>& bucket) {
      for (const Seg& s : bucket) {
        const double d = distanceToSegment(p, s.a, s.b);
        // Ties (streets through the same point) go to an existing road, then to a major street.
        if (d < best - 1e-9 || (d <= best + 1e-9 && rank(s.level) > rank(level))) best = d, level = s.level;
      }
    });
    return best <= maxDistance ? level : StreetLevel::Outline;
  }

 private:
  static int rank(StreetLevel l) { return l == StreetLevel::Existing ? 2 : l == StreetLevel::Major ? 1 : 0; }
  struct Seg {
    Vec2 a, b;
    StreetLevel level;
  };
  UniformGrid<Seg> grid_;
};

/// GEOS 3.11's snap-rounding noder keeps its hot pixels in a KD-tree that degenerates into a list
/// when the points come in spatial order (lines traced side by side): a 20 km city then spends minutes
/// in KdTree::queryNode. A fixed pseudo-random order of the lines keeps the tree balanced; the results
/// do not depend on it (fromLines and the blocks are ordered afterwards by their coordinates).
void shuffleForNoding(std::vector<LineString>& lines) {
  for (std::size_t i = lines.size(); i > 1; --i) std::swap(lines[i - 1], lines[deriveSeed(0x5eed, i) % i]);
}

void boxOf(const MultiPolygon& polygons, Vec2& lo, Vec2& hi) {
  lo = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  hi = lo * -1.0;
  for (const Polygon& p : polygons)
    for (const Vec2& v : p.outer) {
      lo.x = std::min(lo.x, v.x), lo.y = std::min(lo.y, v.y);
      hi.x = std::max(hi.x, v.x), hi.y = std::max(hi.y, v.y);
    }
}

}  // namespace

double roadSpacing(const std::vector<LineString>& roads, const MultiPolygon& boundary,
                   const MultiPolygon& water) {
  geos::Context ctx;
  geos::GeomPtr land = ctx.multiPolygon(boundary);
  if (!water.empty())
    land = ctx.own(GEOSDifference_r(ctx.handle(), land.get(), ctx.multiPolygon(water).get()),
                   "cutting the water out of the boundary");
  double area = 0.0, length = 0.0;
  GEOSArea_r(ctx.handle(), land.get(), &area);
  for (const LineString& l : roads) {
    if (l.size() < 2) continue;
    const geos::GeomPtr on = ctx.own(GEOSIntersection_r(ctx.handle(), ctx.lineString(l).get(), land.get()),
                                     "clipping a road to the land");
    double len = 0.0;
    GEOSLength_r(ctx.handle(), on.get(), &len);
    length += len;
  }
  return length > 0.0 ? 2.0 * area / length : 0.0;
}

StreetNetwork generateStreets(const StreetsInput& input, const StreetsOptions& options,
                              const Progress& progress) {
  if (input.design.size() > options.maxDesignElements)
    throw invalidInput("the design has " + std::to_string(input.design.size()) + " elements; at most " +
                       std::to_string(options.maxDesignElements) + " are accepted");
  if (input.design.empty() && input.fieldLines.empty() && !input.dem)
    throw invalidInput(
        "the street design is empty: give design elements (-design), roads or lines for the field "
        "(-roads, -field-lines) or a DEM (-dem)");
  if (input.boundary.empty()) throw invalidInput("the boundary holds no polygon");
  TraceOptions t = options.trace;
  t.seed = options.seed;
  if (!(t.majorDsep > 0.0) || !(t.minorDsep > 0.0))
    throw invalidOption("-dsep-major and -dsep-minor must be > 0");
  if (!(t.dtestRatio > 0.0) || t.dtestRatio > 1.0)
    throw invalidOption("-dtest-ratio " + std::to_string(t.dtestRatio) +
                        " makes d_test exceed d_sep (it must lie in (0, 1])");
  const PolygonIndex land(input.boundary);
  for (const DesignElement& e : input.design)
    if (!land.contains(e.position))
      throw invalidInput("design element at (" + std::to_string(e.position.x) + ", " +
                         std::to_string(e.position.y) + ") lies outside the boundary");

  Vec2 lo, hi;
  boxOf(input.boundary, lo, hi);
  const double margin = t.majorDsep;
  lo = lo - Vec2{margin, margin}, hi = hi + Vec2{margin, margin};

  StreetNetwork net;
  FieldOptions fo = options.field;
  fo.seed = options.seed;
  if (!(fo.cellSize > 0.0)) fo.cellSize = options.fieldCellRatio * t.minorDsep;
  if (!(fo.noiseWavelength > 0.0)) fo.noiseWavelength = options.noiseWavelengthRatio * t.majorDsep;
  std::vector<DesignElement> elements = input.design;
  const double sigma = options.polylineDecayRatio * t.majorDsep;
  // §4.3: Douglas-Peucker at about one field cell first, so a pixel staircase (a boundary traced
  // from a raster) gives its overall direction rather than alternating 0 and 90 degree elements,
  // which cancel into a degenerate field.
  std::vector<LineString> fieldLines;
  {
    geos::Context ctx;
    for (const LineString& l : input.fieldLines) {
      if (l.size() < 2) continue;
      const geos::GeomPtr simple = ctx.own(GEOSSimplify_r(ctx.handle(), ctx.lineString(l).get(), fo.cellSize),
                                           "simplifying a field line");
      for (LineString& part : ctx.toLines(simple.get()))
        if (part.size() >= 2) fieldLines.push_back(std::move(part));
    }
  }
  const std::vector<DesignElement> fromLines =
      polylineElements(fieldLines, options.polylineSpacingRatio * t.majorDsep, 1.0 / (sigma * sigma));
  elements.insert(elements.end(), fromLines.begin(), fromLines.end());
  net.field =
      buildField(lo, hi, elements, input.dem ? &*input.dem : nullptr, fo, subProgress(progress, 0.0, 0.2));

  TraceDomain domain;
  domain.land = input.boundary;
  domain.water = input.water;
  domain.parks = input.parks;
  if (!input.existingRoads.empty()) {
    // §14: the existing roads inside the boundary (their parts outside it are not this network's).
    geos::Context ctx;
    const geos::GeomPtr boundary = ctx.multiPolygon(input.boundary);
    for (const LineString& l : input.existingRoads) {
      if (l.size() < 2) continue;
      const geos::GeomPtr inside =
          ctx.own(GEOSIntersection_r(ctx.handle(), ctx.lineString(l).get(), boundary.get()),
                  "clipping an existing road to the boundary");
      for (LineString& part : ctx.toLines(inside.get()))
        if (part.size() >= 2 && length(part) > options.nodingTolerance)
          domain.existing.push_back(std::move(part));
    }
  }
  if (input.densitySpec) {
    float top = 0.0f;
    for (float v : input.density.cells)
      if (std::isfinite(v)) top = std::max(top, v);
    domain.densitySpec = input.densitySpec;
    domain.density = input.density;
    for (float& v : domain.density.cells)
      v = (std::isfinite(v) && top > 0.0f) ? std::max(0.0f, v / top) : 0.0f;
  }
  // Seeds: the design elements (a radial centre is degenerate: start one minor spacing east of it),
  // then points along the field's polylines every major d_sep, so major roads grow from them.
  std::vector<Vec2> seeds;
  for (const DesignElement& e : input.design)
    seeds.push_back(e.kind == ElementKind::Radial ? e.position + Vec2{t.minorDsep, 0.0} : e.position);
  for (const LineString& l : input.fieldLines)
    for (const Vec2& p : densified(l, t.majorDsep)) seeds.push_back(p);
  std::vector<Street> traced =
      traceStreets(net.field, domain, seeds, t, &net.stats, subProgress(progress, 0.2, 0.8));
  net.tracedLines = traced.size();

  // §10: node every crossing (GEOS) in one pass over the streets and the outlines of the boundary
  // and the water (which close the blocks); each piece gets the level of the street it lies on, or
  // Outline when it lies on no street.
  std::vector<LineString> lines;
  for (const Street& s : traced) lines.push_back(s.line);
  for (const MultiPolygon* mp : {&input.boundary, &input.water})
    for (const Polygon& p : *mp) {
      lines.push_back(p.outer);
      for (const Ring& h : p.holes) lines.push_back(h);
    }
  shuffleForNoding(lines);
  const PlanarGraph graph = PlanarGraph::fromLines(lines, options.nodingTolerance);
  std::vector<StreetLevel> edgeLevel(graph.edgeCount(), StreetLevel::Outline);
  {
    const LevelLookup lookup(traced, lo, hi, t.minorDsep);
    for (int e = 0; e < static_cast<int>(graph.edgeCount()); ++e) {
      const LineString& l = graph.edge(e).line;
      const std::size_t mid = (l.size() - 1) / 2;
      edgeLevel[static_cast<std::size_t>(e)] =
          lookup.at((l[mid] + l[mid + 1]) * 0.5, 10.0 * options.nodingTolerance);
    }
  }
  reportProgress(progress, 0.85, "noding");
  // §13.6 graph noise: deletions and cut-backs create no crossing, so nothing is noded again.
  std::vector<Street> pieces;
  if (options.noise.fullShare > 0.0 || options.noise.partialShare > 0.0 || options.noise.bendShare > 0.0) {
    GraphNoiseOptions noise = options.noise;
    noise.startIndex = 1 + static_cast<int>(options.seed % 100000);
    pieces = applyGraphNoise(graph, edgeLevel, noise);
  } else {
    for (int e = 0; e < static_cast<int>(graph.edgeCount()); ++e)
      pieces.push_back({graph.edge(e).line, edgeLevel[static_cast<std::size_t>(e)], 0});
  }
  {
    BowOptions bow = options.bow;
    bow.seed = options.seed;
    bow.maxOffset = options.bowMaxOffsetRatio * t.minorDsep;
    bowStreets(pieces, bow);
  }
  // The street graph: its pieces share their end points exactly.
  PlanarGraph streets;
  std::vector<StreetLevel> streetLevel;
  {
    std::map<std::pair<double, double>, int> id;
    for (const Street& s : pieces)
      if (s.level != StreetLevel::Outline)
        for (const Vec2* p : {&s.line.front(), &s.line.back()}) id.emplace(std::make_pair(p->x, p->y), 0);
    for (auto& [p, n] : id) n = streets.addNode({p.first, p.second});
    for (const Street& s : pieces) {
      if (s.level == StreetLevel::Outline) continue;
      const int a = id.at({s.line.front().x, s.line.front().y}),
                b = id.at({s.line.back().x, s.line.back().y});
      if (a == b) continue;  // fromLines never makes loops
      streets.addEdge(a, b, s.line);
      streetLevel.push_back(s.level);
    }
    streets.sortRotations();
  }
  auto levelChange = [&](int n) {
    const auto& es = streets.node(n).edges;
    for (int e : es)
      if (streetLevel[static_cast<std::size_t>(e)] != streetLevel[static_cast<std::size_t>(es.front())])
        return true;
    return false;
  };
  std::vector<char> endNode(streets.nodeCount(), 0);
  for (const std::vector<int>& chain : streets.chains(levelChange)) {
    StreetEdge edge;
    edge.line = streets.chainLine(chain, levelChange);
    edge.level = streetLevel[static_cast<std::size_t>(chain.front())];
    const std::vector<int> ends = streets.chainNodes(chain, levelChange);
    endNode[static_cast<std::size_t>(ends.front())] = endNode[static_cast<std::size_t>(ends.back())] = 1;
    net.streets.push_back(std::move(edge));
  }
  for (int n = 0; n < static_cast<int>(streets.nodeCount()); ++n)
    if (endNode[static_cast<std::size_t>(n)]) net.nodes.push_back({streets.node(n).p, streets.degree(n)});

  // Blocks: faces of the noded streets and outlines (GEOS polygonize, holes kept), inside the boundary
  // and out of the water, in the order of their inner points.
  reportProgress(progress, 0.9, "blocks");
  geos::Context ctx;
  std::vector<geos::GeomPtr> owned;
  std::vector<const GEOSGeometry*> parts;
  for (const Street& s : pieces) {
    owned.push_back(ctx.lineString(s.line));
    parts.push_back(owned.back().get());
  }
  const geos::GeomPtr faces =
      ctx.own(GEOSPolygonize_r(ctx.handle(), parts.data(), static_cast<unsigned>(parts.size())),
              "polygonizing the blocks");
  const PolygonIndex water(input.water), parks(input.parks);
  // The use of a block: gridify's rule for untagged land (issue 20), so a block grown here and one
  // gridify finds between mapped streets take the same use from the same evidence. A block has no
  // buildings yet; its evidence is the class of its bounding streets (minor roads are residential
  // streets, as gridify reads them), and a block where the density raster is zero lies outside the
  // urban extent.
  std::map<std::pair<std::pair<double, double>, std::pair<double, double>>, const char*> segmentClass;
  for (const Street& s : pieces) {
    if (s.level == StreetLevel::Outline) continue;
    const char* cls = s.level == StreetLevel::Minor ? "residential" : "primary";
    for (std::size_t i = 0; i + 1 < s.line.size(); ++i) {
      std::pair<double, double> a{s.line[i].x, s.line[i].y}, b{s.line[i + 1].x, s.line[i + 1].y};
      if (b < a) std::swap(a, b);
      segmentClass.emplace(std::make_pair(a, b), cls);
    }
  }
  gridify::UntaggedLandOptions rule = options.untaggedLand;
  rule.enabled = true;
  if (const std::optional<LandUse> use = parseLandUse(options.defaultUse)) rule.defaultUse = *use;
  auto evidenceOf = [&](const Polygon& face) {
    gridify::BlockEvidence ev;
    ev.cells = 1;
    auto addRing = [&](const Ring& r) {
      for (std::size_t i = 0; i + 1 < r.size(); ++i) {
        std::pair<double, double> a{r[i].x, r[i].y}, b{r[i + 1].x, r[i + 1].y};
        if (b < a) std::swap(a, b);
        const auto it = segmentClass.find({a, b});
        if (it != segmentClass.end()) ev.streetLength[it->second] += distance(r[i], r[i + 1]);
      }
    };
    addRing(face.outer);
    for (const Ring& h : face.holes) addRing(h);
    return ev;
  };
  std::vector<std::pair<std::pair<double, double>, Block>> found;
  for (Polygon& face : ctx.toPolygons(faces.get())) {
    const geos::GeomPtr g = ctx.polygon(face);
    const geos::GeomPtr inner = ctx.own(GEOSPointOnSurface_r(ctx.handle(), g.get()), "a block's inner point");
    double x = 0, y = 0;
    GEOSGeomGetX_r(ctx.handle(), inner.get(), &x);
    GEOSGeomGetY_r(ctx.handle(), inner.get(), &y);
    const Vec2 p{x, y};
    if (!land.contains(p) || water.contains(p) || area(face) <= options.nodingTolerance) continue;
    std::string use;
    if (!parks.empty() && parks.contains(p)) {
      use = "park";
    } else {
      gridify::BlockEvidence ev = evidenceOf(face);
      if (domain.densitySpec) {
        const Vec2 px = domain.densitySpec->transform.worldToPixel(p);
        const int i = static_cast<int>(std::floor(px.x)), j = static_cast<int>(std::floor(px.y));
        ev.external = !domain.density.inside(i, j) || domain.density.at(i, j) <= 0.0f;
      }
      const std::optional<LandUse> inferred = gridify::inferUntaggedUse(ev, rule).first;
      use = inferred ? std::string(landUseName(*inferred)) : options.emptyUse;
    }
    found.push_back({{y, x}, Block{std::move(face), use}});
  }
  std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (auto& f : found) net.blocks.push_back(std::move(f.second));
  reportProgress(progress, 1.0, "blocks");
  return net;
}

}  // namespace urbanvec::streets
