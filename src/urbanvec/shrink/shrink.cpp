// The shrinking pipeline of the thesis (spec §B.0 step list, Table 2 step names): step0 clean (§B.2),
// step1 indirect important streets (§B.3), step2 selection (§B.4), step3&4 clusters (§B.5), step5
// dead ends (§B.6), step6 places (§B.7), step7 raster (§B.8), step8Pre energy (§B.9), step8SC seam
// carving (§B.10), step8Pos back to vector (§B.11), then the measures (§E.4 item 3).
#include "urbanvec/shrink/shrink.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>

#include "urbanvec/core/error.hpp"
#include "urbanvec/shrink/back_to_vector.hpp"
#include "urbanvec/shrink/cleaning.hpp"
#include "urbanvec/shrink/cluster_connection.hpp"
#include "urbanvec/shrink/dead_end_connection.hpp"
#include "urbanvec/shrink/dense_ways.hpp"
#include "urbanvec/shrink/energy.hpp"
#include "urbanvec/shrink/indirect_streets.hpp"
#include "urbanvec/shrink/rasterise.hpp"
#include "urbanvec/shrink/rotation.hpp"
#include "urbanvec/shrink/seam_carving.hpp"
#include "urbanvec/shrink/skeleton.hpp"
#include "urbanvec/shrink/straightening.hpp"
#include "urbanvec/shrink/street_graph.hpp"
#include "urbanvec/shrink/street_selection.hpp"

namespace urbanvec::shrink {

const char* wayKindName(WayKind kind) {
  switch (kind) {
    case WayKind::Important:
      return "important";
    case WayKind::Selected:
      return "selected";
    case WayKind::Connector:
      return "connector";
    case WayKind::DeadEndConnector:
      return "dead_end_connector";
  }
  return "selected";
}

double ShrinkReport::value(const std::string& name) const {
  for (const auto& [k, v] : values)
    if (k == name) return v;
  return std::numeric_limits<double>::quiet_NaN();
}

namespace {
std::string numberText(double v);
}

void validate(const ShrinkOptions& o) {
  auto unit = [](double v, const char* name) {
    if (!(v >= 0.0 && v <= 1.0))
      throw invalidOption(std::string(name) + " must be within 0..1, not " + numberText(v));
  };
  unit(o.selection.shrinkFactor, "shF (-shf)");
  unit(o.connection.impDistBalance, "impDistBalance (-imp-dist-balance)");
  unit(o.carving.grayDistBalance, "grayDistBalance (-gray-dist-balance)");
  if (o.carving.imageSize <= 1)
    throw invalidOption("imageSize (-image-size) must be at least 2 pixels, not " +
                        std::to_string(o.carving.imageSize));
  if (o.carving.verticalSeams < 0 || o.carving.horizontalSeams < 0)
    throw invalidOption("the seam counts (-seams) must not be negative");
  if (!(o.carving.densifySpacing >= 0.0) || !(o.carving.simplifyTolerance >= 0.0))
    throw invalidOption("the densify spacing and simplify tolerance must not be negative");
  if (o.connection.mDegree < 0) throw invalidOption("m-degree (-m-degree) must not be negative");
  if (!(o.selection.proximityThreshold >= 0.0))
    throw invalidOption("proxStrThreshold (-prox-str-threshold) must not be negative");
  for (const auto& [k, v] : o.selection.highwayWeights)
    if (!(v >= 0.0)) throw invalidOption("highway weight of '" + k + "' must not be negative");
}

namespace {

using Clock = std::chrono::steady_clock;

class Timer {
 public:
  explicit Timer(std::vector<StepTime>& out) : out_(out), start_(Clock::now()) {}
  void lap(const char* step) {
    const auto now = Clock::now();
    out_.push_back({step, std::chrono::duration<double>(now - start_).count()});
    start_ = now;
  }

 private:
  std::vector<StepTime>& out_;
  Clock::time_point start_;
};

const double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string numberText(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.10g", v);
  return buffer;
}

std::string seamRange(int from, int to) {
  return from == to ? std::to_string(from) : std::to_string(from) + "-" + std::to_string(to);
}

}  // namespace

ShrinkResult shrinkCity(const ShrinkInput& input, const ShrinkOptions& options, const Progress& progressIn) {
  validate(options);
  const Progress progress = monotonicProgress(progressIn);
  ShrinkResult result;
  ShrinkReport& report = result.report;
  auto put = [&](const char* name, double v) { report.values.emplace_back(name, v); };
  Timer timer(result.timings);

  // step0 (§B.2).
  City city = input.city;
  const std::vector<Place>& places = input.places;
  const CleaningStats cleaning = cleanCity(city, options.cleaning);
  if (city.streets.empty())
    throw invalidInput(cleaning.waysIn == 0
                           ? "the city has no street: no way with a highway tag"
                           : "the city has no street left after cleaning: all " +
                                 std::to_string(cleaning.waysIn) +
                                 " highway ways lie outside the download bounds or have fewer than 2 nodes");
  put("streets_in", cleaning.waysIn);
  put("streets_clean", cleaning.waysOut);
  put("nodes_outside_bounds", cleaning.nodesOutsideBounds);
  reportProgress(progress, 0.02, "cleaning");

  // step1 (§B.3) and step2 (§B.4).
  const StreetGraph graph = buildStreetGraph(city.nodes, city.streets);
  IndirectStats indirect;
  const std::vector<StreetImportance> importance =
      findImportantStreets(city, places, options.selection, &indirect);
  timer.lap("step1");
  const Selection selection = selectStreets(city, graph, importance, options.selection);
  timer.lap("step2");
  put("important_streets", selection.importantCount);
  put("indirect_streets", indirect.nearest + indirect.insideBounding);
  put("selected_streets", selection.selectedCount);
  put("important_selected", selection.importantSelected);
  if (indirect.placesWithoutStreet > 0)
    result.warnings.push_back(std::to_string(indirect.placesWithoutStreet) + " place" +
                              (indirect.placesWithoutStreet == 1 ? " has" : "s have") +
                              " no street within proxStrThreshold (" +
                              numberText(options.selection.proximityThreshold) + " m)");
  reportProgress(progress, 0.05, "selection");

  // step3&4 (§B.5).
  ConnectionStats connection;
  std::vector<char> in = connectClusters(city, graph, selection, importance, options.connection, &connection);
  timer.lap("step3&4");
  put("clusters", connection.clusters);
  put("clusters_joined", connection.joined);
  put("clusters_unreachable", connection.unreachable);
  put("connector_streets", connection.connectorWays);
  put("clusters_removed", connection.removedClusters);
  reportProgress(progress, 0.10, "connecting clusters");

  // step5 (§B.6).
  DeadEndStats deadEnds;
  const std::vector<CityWay> connectors =
      connectDeadEnds(city, graph, in, options.connection.mDegree, -1, &deadEnds);
  timer.lap("step5");
  put("dead_ends", deadEnds.deadEnds);
  put("dead_ends_connected", deadEnds.connected);
  put("dead_ends_remaining", deadEnds.remaining);

  // step6 (§B.7): the skeleton city.
  Skeleton skeleton;
  for (size_t w = 0; w < city.streets.size(); ++w) {
    if (!in[w]) continue;
    SkeletonWay s{city.streets[w], static_cast<int>(w), selection.scores[w].impW, WayKind::Selected,
                  importance[w].place};
    if (importance[w].important)
      s.kind = WayKind::Important;
    else if (in[w] == 2)
      s.kind = WayKind::Connector;
    skeleton.ways.push_back(std::move(s));
  }
  for (const CityWay& way : connectors)
    skeleton.ways.push_back(
        {way, -1, streetTypeWeight(way.highway, options.selection), WayKind::DeadEndConnector, -1});
  for (size_t p = 0; p < places.size(); ++p)
    if (!places[p].shapes.empty()) skeleton.places.push_back(static_cast<int>(p));
  put("skeleton_streets", static_cast<double>(skeleton.ways.size()));
  put("places", static_cast<double>(places.size()));
  timer.lap("step6");
  reportProgress(progress, 0.15, "skeleton");

  // Frozen street nodes (§B.9 item 6): intersections of the skeleton (shared by two ways or with a
  // degree other than 2: crossings, ends).
  const size_t nNodes = city.nodes.size();
  std::vector<int> wayUse(nNodes, 0), lastWay(nNodes, -1);
  std::vector<std::set<int>> neighbours(nNodes);
  for (size_t w = 0; w < skeleton.ways.size(); ++w) {
    const std::vector<int>& ns = skeleton.ways[w].way.nodes;
    for (size_t i = 0; i < ns.size(); ++i) {
      const size_t n = static_cast<size_t>(ns[i]);
      if (lastWay[n] != static_cast<int>(w)) lastWay[n] = static_cast<int>(w), ++wayUse[n];
      if (i > 0 && ns[i - 1] != ns[i]) {
        neighbours[n].insert(ns[i - 1]);
        neighbours[static_cast<size_t>(ns[i - 1])].insert(ns[i]);
      }
    }
  }
  std::vector<char> frozen(nNodes, 0), pinned(nNodes, 0), skeletonNode(nNodes, 0);
  for (size_t n = 0; n < nNodes; ++n) {
    if (wayUse[n] == 0) continue;
    skeletonNode[n] = 1;
    frozen[n] = options.carving.freezeAllStreetNodes || wayUse[n] >= 2 || neighbours[n].size() != 2;
  }
  // A run of unfrozen nodes that closes a loop (both ends the same node) or doubles another run
  // between the same two frozen nodes would collapse when a seam deletes its nodes, taking a neighbour
  // from an intersection: its middle node is frozen too, so the skeleton's topology survives.
  std::set<std::pair<int, int>> runs;
  for (const SkeletonWay& s : skeleton.ways) {
    const std::vector<int>& ns = s.way.nodes;
    size_t i = 0;
    while (i + 1 < ns.size()) {
      size_t j = i + 1;
      while (j + 1 < ns.size() && !frozen[static_cast<size_t>(ns[j])]) ++j;
      const std::pair<int, int> key{std::min(ns[i], ns[j]), std::max(ns[i], ns[j])};
      if (j > i + 1 && (ns[i] == ns[j] || !runs.insert(key).second))
        frozen[static_cast<size_t>(ns[(i + j) / 2])] = 1;
      if (j == i + 1) runs.insert(key);
      i = j;
    }
  }
  for (int p : skeleton.places)
    for (const auto& shape : places[static_cast<size_t>(p)].shapes)
      for (int n : shape) pinned[static_cast<size_t>(n)] = 1;

  // Rotation trick (§B.11, §4.6.1).
  double minX = std::numeric_limits<double>::infinity(), minY = minX, maxX = -minX, maxY = -minX;
  std::vector<char> used(nNodes, 0);
  for (const CityWay& way : city.streets)
    for (int n : way.nodes) used[static_cast<size_t>(n)] = 1;
  for (int p : skeleton.places)
    for (const auto& shape : places[static_cast<size_t>(p)].shapes)
      for (int n : shape) used[static_cast<size_t>(n)] = 1;
  for (const auto& place : places)
    for (int n : place.boundingRing) used[static_cast<size_t>(n)] = 1;
  for (size_t n = 0; n < nNodes; ++n)
    if (used[n]) {
      const Vec2 p = city.nodes[n].p;
      minX = std::min(minX, p.x), maxX = std::max(maxX, p.x), minY = std::min(minY, p.y),
      maxY = std::max(maxY, p.y);
    }
  const Vec2 centre{(minX + maxX) / 2, (minY + maxY) / 2};
  double rotation = options.post.rotationDegrees;
  if (options.post.autoRotate) {
    std::vector<std::pair<Vec2, Vec2>> segments;
    for (const SkeletonWay& s : skeleton.ways)
      for (size_t i = 1; i < s.way.nodes.size(); ++i)
        segments.push_back({city.nodes[static_cast<size_t>(s.way.nodes[i - 1])].p,
                            city.nodes[static_cast<size_t>(s.way.nodes[i])].p});
    const double bearing = dominantBearing(segments);
    rotation = -(bearing > 45.0 ? bearing - 90.0 : bearing);
  }
  put("rotation_degrees", rotation);
  std::vector<Vec2> pos(nNodes);
  for (size_t n = 0; n < nNodes; ++n)
    pos[n] = rotation != 0.0 ? rotatePoint(city.nodes[n].p, centre, rotation) : city.nodes[n].p;
  auto unrotate = [&](const Vec2& p) { return rotation != 0.0 ? rotatePoint(p, centre, -rotation) : p; };

  // step7 (§B.8).
  double fMinX = std::numeric_limits<double>::infinity(), fMinY = fMinX, fMaxX = -fMinX, fMaxY = -fMinX;
  for (size_t n = 0; n < nNodes; ++n)
    if (used[n]) {
      fMinX = std::min(fMinX, pos[n].x), fMaxX = std::max(fMaxX, pos[n].x);
      fMinY = std::min(fMinY, pos[n].y), fMaxY = std::max(fMaxY, pos[n].y);
    }
  const RasterFrame frame = frameFor(fMinX, fMinY, fMaxX, fMaxY, options.carving.imageSize);
  put("image_width", frame.width);
  put("image_height", frame.height);
  put("cell_size", frame.cell);
  if (options.carving.verticalSeams >= frame.width)
    throw invalidOption("-seams: " + std::to_string(options.carving.verticalSeams) +
                        " vertical seams, but the skeleton image is " + std::to_string(frame.width) +
                        " pixels wide (imageSize " + std::to_string(options.carving.imageSize) +
                        "); at most " + std::to_string(frame.width - 1) + " can be removed");
  if (options.carving.horizontalSeams >= frame.height)
    throw invalidOption("-seams: " + std::to_string(options.carving.horizontalSeams) +
                        " horizontal seams, but the skeleton image is " + std::to_string(frame.height) +
                        " pixels high (imageSize " + std::to_string(options.carving.imageSize) +
                        "); at most " + std::to_string(frame.height - 1) + " can be removed");
  std::vector<InkLine> inkLines;
  for (const SkeletonWay& s : skeleton.ways) {
    InkLine line;
    line.ink = static_cast<float>(255.0 * std::clamp(s.impW, 0.0, 1.0));
    for (int n : s.way.nodes) line.points.push_back(pos[static_cast<size_t>(n)]);
    inkLines.push_back(std::move(line));
  }
  std::vector<LandmarkShape> landmarks;
  for (int p : skeleton.places)
    for (const auto& shape : places[static_cast<size_t>(p)].shapes) {
      LandmarkShape l;
      l.place = p;
      for (int n : shape) l.points.push_back(pos[static_cast<size_t>(n)]);
      landmarks.push_back(std::move(l));
    }
  std::vector<Vec2> frozenPoints;
  for (size_t n = 0; n < nNodes; ++n)
    if (frozen[n]) frozenPoints.push_back(pos[n]);
  const SkeletonRaster raster =
      rasteriseSkeleton(frame, inkLines, landmarks, frozenPoints, options.carving.landmarkFreeze);
  timer.lap("step7");
  reportProgress(progress, 0.2, "rasterising");

  // step8Pre (§B.9).
  std::vector<Vec2> before(nNodes);
  for (size_t n = 0; n < nNodes; ++n) before[n] = city.nodes[n].p;
  std::vector<std::vector<int>> waysBefore, waysAfter;
  for (const SkeletonWay& s : skeleton.ways) waysBefore.push_back(s.way.nodes);
  const bool dense = options.carving.densifySpacing > 0.0;
  std::vector<Vec2> pointPos = pos, pointBefore = before;
  const std::vector<std::vector<int>> wayPoints =
      dense ? densifyWays(waysBefore, options.carving.densifySpacing * frame.cell, pointPos, pointBefore)
            : waysBefore;
  const size_t nPoints = pointPos.size();
  const std::vector<float> energy = seamEnergy(raster, options.carving.grayDistBalance);
  // The crossing guard of seam carving: every dense point in pixel units, as PointMapper places it.
  SeamWays seamWays;
  if (dense && options.carving.separateWays) {
    seamWays = seamWaysOf(wayPoints, pointPos, frame);
    for (int p : skeleton.places) {  // each place's nodes, as the arrangement measure takes them
      std::vector<int> nodes;
      for (const auto& shape : places[static_cast<size_t>(p)].shapes)
        nodes.insert(nodes.end(), shape.begin(), shape.end());
      if (!nodes.empty()) seamWays.places.push_back(std::move(nodes));
    }
  }
  size_t frozenPixels = 0;
  for (int owner : raster.freezeOwner) frozenPixels += owner != kNotFrozen;
  put("frozen_pixels", static_cast<double>(frozenPixels));
  timer.lap("step8Pre");

  // step8SC (§B.10).
  const CarveResult carve =
      carveSeams(energy, frame.width, frame.height, options.carving.verticalSeams,
                 options.carving.horizontalSeams, options.carving.order, subProgress(progress, 0.25, 0.85),
                 seamWays.ways.empty() ? nullptr : &seamWays, options.carving.threads);
  put("crossing_guard_pixels", static_cast<double>(carve.crossingFrozen));
  put("landmark_order_guard_pixels", static_cast<double>(carve.orderFrozen));
  put("crossing_guard_retries", static_cast<double>(carve.seamRetries));
  put("cumulative_cells_per_seam", carve.seams.empty() ? 0.0
                                                       : static_cast<double>(carve.cellsUpdated) /
                                                             static_cast<double>(carve.seams.size()));
  timer.lap("step8SC");
  put("seams_vertical_requested", options.carving.verticalSeams);
  put("seams_horizontal_requested", options.carving.horizontalSeams);
  put("seams_vertical", carve.verticalRemoved);
  put("seams_horizontal", carve.horizontalRemoved);
  put("final_width", carve.width);
  put("final_height", carve.height);
  auto blockedNote = [&](bool vertical, int requested, int removed, int at) {
    if (removed >= requested) return;
    const char* dir = vertical ? "vertical" : "horizontal";
    std::string why;
    if (at >= 0) {
      const int owner = raster.freezeOwner[static_cast<size_t>(at)];
      const int line = vertical ? at / frame.width : at % frame.width;
      why = std::string("original ") + (vertical ? "row " : "column ") + std::to_string(line) +
            " is frozen from edge to edge";
      std::set<int> owners;
      for (int k = 0; k < (vertical ? frame.width : frame.height); ++k) {
        const size_t px =
            vertical ? static_cast<size_t>(line) * static_cast<size_t>(frame.width) + static_cast<size_t>(k)
                     : static_cast<size_t>(k) * static_cast<size_t>(frame.width) + static_cast<size_t>(line);
        (void)owner;
        owners.insert(raster.freezeOwner[px]);
      }
      std::string names;
      for (int o : owners)
        if (o >= 0)
          names += (names.empty() ? "" : ", ") + std::string("'") +
                   (places[static_cast<size_t>(o)].name.empty() ? places[static_cast<size_t>(o)].id
                                                                : places[static_cast<size_t>(o)].name) +
                   "'";
      why += names.empty() ? " by street intersections"
                           : " by the landmark" + std::string(owners.size() > 2 ? "s " : " ") + names +
                                 (owners.count(kFrozenStreetNode) ? " and street intersections" : "");
    } else if (vertical ? carve.verticalBlockedByGuard : carve.horizontalBlockedByGuard) {
      why = "every remaining path crosses a pixel the guard froze (" + std::to_string(carve.crossingFrozen) +
            " pixels where a seam would have made two streets cross or touch, " +
            std::to_string(carve.orderFrozen) +
            " where it would have flipped the order of two landmarks); a path avoiding the landmarks and "
            "street "
            "intersections alone exists";
    } else {
      why = "every path across the image crosses a frozen pixel (landmarks, street intersections, the " +
            std::to_string(carve.crossingFrozen) +
            " pixels where a seam would have made two streets cross or touch and the " +
            std::to_string(carve.orderFrozen) + " where it would have flipped the order of two landmarks)";
    }
    report.notes.push_back(std::string(dir) + " seams " + seamRange(removed + 1, requested) + " of " +
                           std::to_string(requested) + " could not be removed: " + why);
    result.warnings.push_back(report.notes.back());
  };
  blockedNote(true, options.carving.verticalSeams, carve.verticalRemoved, carve.verticalBlockedAt);
  blockedNote(false, options.carving.horizontalSeams, carve.horizontalRemoved, carve.horizontalBlockedAt);

  // step8Pos (§B.11). Every skeleton way is densified (synthetic points at most densifySpacing pixels
  // apart) and each point moves with its own pixel, so the ways follow the carved raster; the synthetic
  // points and the nodes whose pixel a seam removed are then dropped where that creates no crossing.
  const PointMapper mapper(frame, carve);
  put("synthetic_points", static_cast<double>(nPoints - nNodes));
  std::vector<Vec2> after(nPoints, Vec2{kNaN, kNaN});
  std::vector<char> removable(nPoints, 0), carved(nPoints, 0);
  // Points of a segment shared by several ways stay: dropping them in one way and not the other would
  // split the shared segment.
  std::vector<int> pointUse(nPoints, 0);
  for (const auto& points : wayPoints) {
    std::set<int> distinct(points.begin(), points.end());
    for (int n : distinct) ++pointUse[static_cast<size_t>(n)];
  }
  for (size_t n = 0; n < nPoints; ++n) {
    const bool synthetic = n >= nNodes;
    if (!synthetic && !skeletonNode[n] && !pinned[n]) continue;
    const bool keep = options.carving.keepCarvedNodes || (!synthetic && pinned[n]);
    Vec2 q;
    if (dense) {
      if (!mapper.map(pointPos[n], true, q)) continue;
      carved[n] = !synthetic && !keep && !mapper.survives(pointPos[n]);
      removable[n] = (synthetic || carved[n]) && pointUse[n] == 1;
    } else if (!mapper.map(pointPos[n], keep, q)) {
      continue;
    }
    after[n] = unrotate(q);
  }
  if (options.post.straighten) {
    std::vector<char> fixed = pinned;
    fixed.resize(nPoints, 0);
    const std::vector<Vec2> carvedPos = after;
    put("straightened_ways", straightenWays(wayPoints, pointBefore, after, fixed,
                                            options.post.straightTolerance, options.post.straightenRounds));
    // Straightening moves points after carving: a way whose straightened line would cross another way
    // (or pass over another way's point) keeps its carved line.
    put("straighten_refused", revertCrossingMoves(wayPoints, carvedPos, after));
  }
  for (const std::vector<int>& points : wayPoints) {
    std::vector<int> kept;
    for (int n : points) {
      const Vec2 p = after[static_cast<size_t>(n)];
      if (!std::isfinite(p.x) || (!kept.empty() && kept.back() == n)) continue;
      // A removable point on top of the previous one adds nothing.
      if (!kept.empty() && removable[static_cast<size_t>(n)] && after[static_cast<size_t>(kept.back())] == p)
        continue;
      kept.push_back(n);
    }
    waysAfter.push_back(std::move(kept));
  }
  if (dense) {
    SimplifyStats simplify;
    waysAfter = simplifyWithoutCrossings(waysAfter, after, removable, carved,
                                         options.carving.simplifyTolerance * frame.cell, &simplify);
    put("points_kept_to_avoid_crossings", simplify.keptCarved);
  }
  {
    std::vector<char> present(nNodes, 0);
    for (const auto& points : waysAfter)
      for (int n : points)
        if (static_cast<size_t>(n) < nNodes) present[static_cast<size_t>(n)] = 1;
    int dropped = 0;
    for (const auto& way : waysBefore)
      for (int n : way)
        if (!present[static_cast<size_t>(n)]) ++dropped, present[static_cast<size_t>(n)] = 1;
    put("nodes_dropped", dropped);
  }
  int lostWays = 0;
  for (size_t w = 0; w < skeleton.ways.size(); ++w) {
    const SkeletonWay& s = skeleton.ways[w];
    const std::vector<int>& kept = waysAfter[w];
    if (kept.size() < 2) {
      ++lostWays;
      continue;
    }
    ShrunkWay out{s.way.osmId, s.way.highway, s.way.name, s.impW, wayKindName(s.kind), {}};
    for (int n : kept) out.line.push_back(after[static_cast<size_t>(n)]);
    result.streets.push_back(std::move(out));
  }
  put("streets_lost", lostWays);
  for (int p : skeleton.places) {
    const Place& place = places[static_cast<size_t>(p)];
    for (size_t k = 0; k < place.shapes.size(); ++k) {
      const auto& shape = place.shapes[k];
      ShrunkPlace out{place.id,
                      k < place.shapeIds.size() ? place.shapeIds[k] : place.osmId,
                      place.name,
                      place.appearW,
                      {}};
      LineString line;
      for (int n : shape) line.push_back(after[static_cast<size_t>(n)]);
      if (line.size() == 1)
        out.geometry = line[0];
      else if (line.size() >= 4 && shape.front() == shape.back())
        out.geometry = Polygon{line, {}};
      else
        out.geometry = line;
      result.places.push_back(std::move(out));
    }
  }
  if (options.post.fullMap) {
    for (const CityWay& way : city.streets) {
      ShrunkWay out{way.osmId, way.highway, way.name, 0.0, "street", {}};
      for (int n : way.nodes) {
        Vec2 q;
        if (!mapper.map(pos[static_cast<size_t>(n)], true, q)) continue;
        q = unrotate(q);
        if (out.line.empty() || out.line.back() != q) out.line.push_back(q);
      }
      if (out.line.size() >= 2) result.fullStreets.push_back(std::move(out));
    }
  }
  for (size_t k = 0; k < carve.seams.size(); ++k) {
    SeamLine seam{static_cast<int>(k) + 1, carve.seams[k].vertical, {}};
    for (int px : carve.seams[k].pixels) seam.line.push_back(unrotate(mapper.pixelCentre(px)));
    result.seams.push_back(std::move(seam));
  }
  timer.lap("step8Pos");
  reportProgress(progress, 0.9, "back to vector");

  // Measures (§E.4 item 3; issue 19).
  MeasureInput mi;
  mi.waysBefore = std::move(waysBefore);
  mi.waysAfter = std::move(waysAfter);
  mi.before = pointBefore;
  mi.after = after;
  for (int p : skeleton.places) mi.landmarks.push_back(places[static_cast<size_t>(p)].shapes);
  for (const CityWay& way : city.streets) mi.cityWays.push_back(way.nodes);
  const ShrinkMeasures& m = result.measures = measureShrink(mi);
  const double ideal =
      static_cast<double>(carve.width) * carve.height / (static_cast<double>(frame.width) * frame.height);
  put("area_ideal", ideal);
  put("area_kept", m.areaKept);
  put("landmark_max_deviation", m.landmarkMaxDeviation);
  put("landmark_pairs", m.landmarkPairs);
  put("order_violations_x", m.orderViolationsX);
  put("order_violations_y", m.orderViolationsY);
  put("bearing_change_median", m.bearingChangeMedian);
  put("distance_ratio_min", m.distanceRatioMin);
  put("distance_ratio_median", m.distanceRatioMedian);
  put("distance_ratio_max", m.distanceRatioMax);
  put("crossings_before", m.crossingsBefore);
  put("crossings_after", m.crossingsAfter);
  put("new_crossings", m.newCrossings);
  put("intersections_before", m.intersectionsBefore);
  put("intersections_kept", m.intersectionsKept);
  put("components_before", m.componentsBefore);
  put("components_after", m.componentsAfter);
  put("dead_ends_before", m.deadEndsBefore);
  put("new_dead_ends", m.newDeadEnds);
  put("entropy_before", m.entropyBefore);
  put("entropy_after", m.entropyAfter);
  put("right_angle_share_before", m.rightAngleShareBefore);
  put("right_angle_share_after", m.rightAngleShareAfter);
  put("angle_deviation_before", m.angleDeviationBefore);
  put("angle_deviation_after", m.angleDeviationAfter);
  put("blocks_before", m.blocksBefore);
  put("blocks_after", m.blocksAfter);
  put("mean_block_area_before", m.meanBlockAreaBefore);
  put("mean_block_area_after", m.meanBlockAreaAfter);
  put("blocks_city", m.blocksCity);
  put("mean_block_area_city", m.meanBlockAreaCity);
  timer.lap("measures");
  reportProgress(progress, 1.0, "measures");
  return result;
}

}  // namespace urbanvec::shrink
