// The cadastre pipeline (spec pueyo-urban-data.md §A.2, Fig. 7): clean data (§A.4-§A.5), blocks
// (§A.6), buildings (§A.7), heights (§A.8). See cadastre.hpp.
#include "urbanvec/cadastre/cadastre.hpp"

#include <algorithm>
#include <exception>
#include <thread>
#include <unordered_map>

#include "urbanvec/cadastre/buildings.hpp"
#include "urbanvec/cadastre/circuits.hpp"
#include "urbanvec/cadastre/floor_labels.hpp"
#include "urbanvec/cadastre/geometric_adjustment.hpp"
#include "urbanvec/cadastre/pre_blocks.hpp"
#include "urbanvec/cadastre/segment_cleaning.hpp"
#include "urbanvec/cadastre/vertex_collapsing.hpp"
#include "urbanvec/cadastre/vertex_merging.hpp"
#include "urbanvec/core/error.hpp"

namespace urbanvec::cadastre {
namespace {

void addGraphStats(CadastreReport& r, const GraphStats& g) {
  r.cornersClosed += g.cornersClosed;
  r.undershootsToSegment += g.undershootsToSegment;
  r.undershootsToVertex += g.undershootsToVertex;
  r.overshootsCut += g.overshootsCut;
  r.hooksCut += g.hooksCut;
  r.fringeEdgesRemoved += g.fringeEdgesRemoved;
  r.verticesStraightened += g.verticesStraightened;
}

/// Moves every output vertex found among `from` to the same index of `to`, and makes the moved
/// polygons valid again (a moved vertex may fold a thin polygon).
void moveVertices(CadastreResult& r, const std::vector<Vec2>& from, const std::vector<Vec2>& to,
                  double minArea) {
  std::unordered_map<std::pair<std::uint64_t, std::uint64_t>, Vec2, CoordinateHash> target;
  target.reserve(from.size());
  for (std::size_t i = 0; i < from.size(); ++i)
    if (from[i] != to[i]) target.emplace(coordinateKey(from[i]), to[i]);
  auto move = [&](MultiPolygon& shape) {
    MultiPolygon out;
    for (Polygon& p : shape) {
      bool moved = false;
      auto ring = [&](Ring& rg) {
        for (Vec2& v : rg) {
          auto it = target.find(coordinateKey(v));
          if (it != target.end()) v = it->second, moved = true;
        }
      };
      ring(p.outer);
      for (Ring& h : p.holes) ring(h);
      if (!moved) {
        out.push_back(std::move(p));
        continue;
      }
      for (Polygon& part : validParts(p, minArea)) out.push_back(std::move(part));
    }
    shape = std::move(out);
  };
  for (BlockOut& b : r.blocks) move(b.shape);
  for (AreaOut& a : r.subBlocks) move(a.shape);
  for (AreaOut& a : r.courtyards) move(a.shape);
  for (AreaOut& a : r.parcels) move(a.shape);
  for (BuildingOut& b : r.buildings) move(b.shape);
}

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

}  // namespace

CadastreResult structureCadastre(const std::vector<CadLine>& lines, const std::vector<CadLabel>& labels,
                                 const CadastreOptions& o, const Progress& progress) {
  if (!(o.collapsingThreshold > 0.0))
    throw invalidOption("-collapse " + number(o.collapsingThreshold) + " must be > 0");
  if (!(o.blockThreshold > 0.0))
    throw invalidOption("-block-threshold " + number(o.blockThreshold) + " must be > 0");
  if (o.collapsingThreshold > o.blockThreshold)
    throw invalidOption("-collapse " + number(o.collapsingThreshold) + " is larger than -block-threshold " +
                        number(o.blockThreshold) +
                        "; the Collapsing Threshold must not exceed the Block Threshold");
  CadastreResult result;
  CadastreReport& rep = result.report;
  for (const CadLine& l : lines) {
    if (l.layer & kBlockLayer) ++rep.blockEntities;
    if (l.layer & kLotLayer) ++rep.lotEntities;
    if (l.layer & kBuildingLayer) ++rep.buildingEntities;
  }
  rep.labelEntities = labels.size();

  // §A.4 vertex cleaning, §A.5 segment cleaning.
  CollapseStats cs;
  Linework lw = collapseVertices(lines, o.collapsingThreshold, cs, subProgress(progress, 0.0, 0.15),
                                 o.thesisRevert, o.freeEndsOnly, o.closestFirst);
  rep.inputVertices = cs.inputVertices;
  rep.outputVertices = cs.outputVertices;
  rep.collapsedShare = cs.collapsedShare();
  rep.revertedCollapses = cs.reverted;
  rep.zeroLengthSegments = cs.zeroLengthSegments;
  SegmentCleaningStats ss;
  cleanSegments(lw, o.collapsingThreshold, ss, subProgress(progress, 0.15, 0.25), o.snapJoined);
  rep.duplicateSegments = ss.duplicateSegments;
  rep.verticesOnSegments = ss.verticesOnSegments;
  rep.cornersKeptOff = ss.cornersKeptOff;
  // The drawing's noise: the spread of the copies of a vertex across their segments (0 when they coincide).
  const double noise = copyNoise(lw);
  // Split vertices: the copies of one drawn vertex left on several vertices merge (noisy drawings only).
  if (o.mergeSplit > 0.0) {
    if (noise > kCleanNoise) {
      MergeStats ms;
      mergeSplitVertices(lw, o.mergeSplit * noise, o.sliverWidth, ms);
      rep.splitVerticesMerged = ms.merged;
      rep.mergesRefusedDrawn = ms.refusedDrawn;
      rep.mergesRefusedFace = ms.refusedFace;
      rep.mergesRefusedCrossing = ms.refusedCrossing;
    }
  }
  // Geometric adjustment: computed now, applied to the output polygons at the end, so that every
  // topological decision below (gap repair, circuits, slivers, labels) is taken on the means of the
  // copies as before and only the vertices' positions change.
  std::vector<Vec2> adjusted;
  if (o.adjust) {
    AdjustmentOptions ao;
    ao.straightAngle = o.straightAngle;
    ao.rightAngle = o.rightAngle;
    AdjustmentStats as;
    adjusted = adjustedVertices(lw, ao, as);
    rep.adjustmentNoise = as.noise;
    rep.straightConstraints = as.straightConstraints;
    rep.rightAngleConstraints = as.rightConstraints;
    rep.verticesAdjusted = as.verticesMoved;
  }

  const double tolerance = o.straightenShare * o.collapsingThreshold;
  // §A.6 blocks: pre-block graph of the block layer, its circuits, sub-blocks and courtyards.
  GraphStats gs;
  const PlanarGraph blockGraph =
      structuredGraph(lw, kBlockLayer, o.blockThreshold, gs, subProgress(progress, 0.25, 0.4), tolerance);
  addGraphStats(rep, gs);
  int preBlockCount = 0;
  const std::vector<int> preBlockOf = preBlocks(blockGraph, o.blockThreshold, &preBlockCount);
  rep.preBlocks = static_cast<std::size_t>(preBlockCount);
  const Circuits bc = findCircuits(blockGraph, o.minFaceArea, o.sliverWidth);
  rep.slivers += bc.slivers;
  // Components at even depth are blocks, at odd depth courtyards of the block around them.
  std::vector<int> blockOfComponent(bc.outlines.size(), -1);
  std::vector<int> componentOfNode(blockGraph.nodeCount(), -1);
  {
    int count = 0;
    const std::vector<int> comp = blockGraph.components(&count);
    for (size_t n = 0; n < comp.size(); ++n) componentOfNode[n] = comp[n];
  }
  std::vector<int> preBlockOfComponent(bc.outlines.size(), -1);
  for (size_t n = 0; n < componentOfNode.size(); ++n)
    preBlockOfComponent[static_cast<size_t>(componentOfNode[n])] = preBlockOf[n];
  // Beyond the thesis: a closed ring inside a block that holds lot or building linework is a block of
  // its own enclosed by the other (a cadastral block filling another's hole), not an empty courtyard.
  std::vector<char> enclosedBlock(bc.outlines.size(), 0);
  {
    std::vector<int> candidates;
    for (size_t k = 0; k < bc.outlines.size(); ++k)
      if (bc.depth[k] % 2 == 1 && bc.outlines[k].size() >= 4) candidates.push_back(static_cast<int>(k));
    if (!candidates.empty()) {
      CellGrid grid(8.0);
      for (int k : candidates) {
        grid.insertBox(boxOf(bc.outlines[static_cast<size_t>(k)]), k);
      }
      for (const Segment& sg : lw.segments) {
        if (!(sg.layers & (kLotLayer | kBuildingLayer)) || (sg.layers & kBlockLayer)) continue;
        const Vec2 m =
            (lw.vertices[static_cast<size_t>(sg.a)] + lw.vertices[static_cast<size_t>(sg.b)]) / 2.0;
        grid.query(m.x, m.y, m.x, m.y, [&](int k) {
          const Ring& ring = bc.outlines[static_cast<size_t>(k)];
          if (enclosedBlock[static_cast<size_t>(k)] || !pointInRing(m, ring)) return;
          // Strictly inside: not on the ring itself.
          double d = 1e300;
          for (size_t i = 1; i < ring.size(); ++i)
            d = std::min(d, distanceToSegment(m, ring[i - 1], ring[i]));
          if (d > o.collapsingThreshold) enclosedBlock[static_cast<size_t>(k)] = 1;
        });
      }
      // A number-of-floors label inside the ring also makes it a block (a building fills it).
      for (const CadLabel& l : labels) {
        int floors = -1;  // parsed once, when the label falls in a candidate ring
        grid.query(l.p.x, l.p.y, l.p.x, l.p.y, [&](int k) {
          if (enclosedBlock[static_cast<size_t>(k)] || !pointInRing(l.p, bc.outlines[static_cast<size_t>(k)]))
            return;
          if (floors < 0) floors = parseFloorLabel(l.text).above > 0 ? 1 : 0;
          if (floors == 1) enclosedBlock[static_cast<size_t>(k)] = 1;
        });
      }
    }
    for (char e : enclosedBlock) rep.enclosedBlocks += e ? 1 : 0;
  }
  auto isBlock = [&](size_t k) { return bc.depth[k] % 2 == 0 || enclosedBlock[k]; };
  // Blocks in order of their components (deterministic: by lowest node id).
  std::vector<Polygon> blockAreas;
  std::vector<int> blockAreaOwner;
  // Per component: whether it has a bounded face, and the components nested in one of its faces (in
  // increasing order), so that blocks and their courtyards are found in linear time.
  std::vector<char> componentHasFace(bc.outlines.size(), 0);
  for (int fc : bc.faceComponent) componentHasFace[static_cast<size_t>(fc)] = 1;
  std::vector<std::vector<size_t>> nestedIn(bc.outlines.size());
  for (size_t j = 0; j < bc.outlines.size(); ++j) {
    const int pf = bc.parentFace[j];
    if (pf >= 0) nestedIn[static_cast<size_t>(bc.faceComponent[static_cast<size_t>(pf)])].push_back(j);
  }
  for (size_t k = 0; k < bc.outlines.size(); ++k) {
    if (!isBlock(k) || bc.outlines[k].size() < 4) continue;
    if (!componentHasFace[k]) continue;  // a pre-block without a circuit is eliminated
    blockOfComponent[k] = static_cast<int>(result.blocks.size());
    BlockOut b;
    b.preBlock = preBlockOfComponent[k];
    Polygon outline{bc.outlines[k], {}};
    for (size_t j : nestedIn[k]) {
      if (enclosedBlock[j]) continue;
      Ring hole = bc.outlines[j];
      std::reverse(hole.begin(), hole.end());
      outline.holes.push_back(std::move(hole));
      ++b.courtyards;
    }
    b.shape = validParts(outline, o.minFaceArea);
    result.blocks.push_back(std::move(b));
  }
  if (result.blocks.empty())
    throw invalidInput(
        "no closed block was found in the block layer: its lines do not form any circuit (check "
        "-block-layer, or raise -block-threshold / -collapse)");
  for (size_t f = 0; f < bc.faces.size(); ++f) {
    const int comp = bc.faceComponent[f];
    const int block = blockOfComponent[static_cast<size_t>(comp)];
    if (block >= 0) {
      for (Polygon& part : validParts(bc.faces[f], o.minFaceArea)) {
        blockAreas.push_back(part);
        blockAreaOwner.push_back(block);
        result.subBlocks.push_back({{part}, block});
      }
      ++result.blocks[static_cast<size_t>(block)].subBlocks;
    } else {
      // A face of a courtyard component: part of the courtyard of the enclosing block.
      const int pf = bc.parentFace[static_cast<size_t>(comp)];
      const int encloser =
          pf >= 0 ? blockOfComponent[static_cast<size_t>(bc.faceComponent[static_cast<size_t>(pf)])] : -1;
      result.courtyards.push_back({validParts(bc.faces[f], o.minFaceArea), encloser});
    }
  }
  rep.blocks = result.blocks.size();
  rep.subBlocks = result.subBlocks.size();
  rep.courtyards = result.courtyards.size();
  const BlockLocator locator(blockAreas, blockAreaOwner);
  reportProgress(progress, 0.5, "parcels");

  // Parcels (beyond the thesis): circuits of block + lot linework inside the blocks. Independent of the
  // building graph below, so with two or more threads both are built side by side; each writes only its
  // own variables, so the output does not depend on the thread count.
  auto parcels = [&](const Progress& parcelProgress) {
    GraphStats pg;
    const PlanarGraph g =
        structuredGraph(lw, kBlockLayer | kLotLayer, o.blockThreshold, pg, parcelProgress, tolerance);
    const Circuits pc = findCircuits(g, o.minFaceArea, o.sliverWidth);
    std::size_t outside = 0;
    for (Localised& l : localise(pc.faces, locator, o.minFaceArea, outside))
      result.parcels.push_back({std::move(l.shape), l.block});
  };
  const unsigned threads =
      o.threads > 0 ? static_cast<unsigned>(o.threads) : std::max(1U, std::thread::hardware_concurrency());
  std::thread parcelWorker;
  std::exception_ptr parcelError;
  if (threads >= 2) {
    parcelWorker = std::thread([&] {
      try {
        parcels(Progress{});  // progress is reported by the building graph on this thread
      } catch (...) {
        parcelError = std::current_exception();
      }
    });
  } else {
    parcels(subProgress(progress, 0.5, 0.65));
  }
  auto joinParcels = [&] {
    if (parcelWorker.joinable()) parcelWorker.join();
  };

  // §A.7 buildings: lot and building layers together with the block layer, circuits again.
  GraphStats bg;
  PlanarGraph g;
  try {
    g = structuredGraph(lw, kBlockLayer | kLotLayer | kBuildingLayer, o.blockThreshold, bg,
                        subProgress(progress, 0.65, 0.85), tolerance);
  } catch (...) {
    joinParcels();
    throw;
  }
  addGraphStats(rep, bg);
  Circuits ec;
  std::vector<Localised> outsideFaces;
  std::vector<Localised> elements;
  try {
    // Beyond the thesis: on a drawing whose copies coincide, a thin face holding a number-of-floors
    // label is a building part, not a sliver.
    std::vector<Vec2> floorLabelPoints;
    if (o.keepLabelledThin && !(noise > kCleanNoise))
      for (const CadLabel& l : labels)
        if (parseFloorLabel(l.text).above > 0) floorLabelPoints.push_back(l.p);
    ec = findCircuits(g, o.minFaceArea, o.sliverWidth, floorLabelPoints);
    rep.labelledThinKept = ec.thinKept;
    elements = localise(ec.faces, locator, o.minFaceArea, rep.facesOutsideBlocks, &outsideFaces);
  } catch (...) {
    joinParcels();
    throw;
  }
  joinParcels();
  if (parcelError) std::rethrow_exception(parcelError);
  rep.parcels = result.parcels.size();
  rep.slivers += ec.slivers;
  const std::size_t inBlocks = elements.size();
  for (Localised& l : outsideFaces) elements.push_back(std::move(l));
  reportProgress(progress, 0.9, "heights");

  // §A.8 heights from the number-of-floors labels.
  std::vector<Vec2> labelPoints;
  std::vector<FloorLabel> parsed;
  std::vector<int> labelIndex;
  for (const CadLabel& l : labels) {
    FloorLabel f = parseFloorLabel(l.text);
    if (!f.valid) {
      ++rep.labelsNotNumbers;
      continue;
    }
    if (f.ignoredParts > 0) ++rep.labelSuffixesIgnored;
    labelPoints.push_back(l.p);
    parsed.push_back(f);
    labelIndex.push_back(static_cast<int>(&l - labels.data()));
  }
  const std::vector<int> chosen =
      assignLabels(elements, labelPoints, o.labelSearchDistance, rep.labelsSnapped, rep.labelsUnmatched,
                   rep.polygonsWithSeveralLabels);
  for (size_t i = 0; i < elements.size(); ++i) {
    // A circuit outside every block is kept as a building only when a label gives it floors (a
    // building drawn beyond the block layer), not when it is an enclosed piece of street.
    if (i >= inBlocks) {
      if (chosen[i] < 0 || parsed[static_cast<size_t>(chosen[i])].above < 1) continue;
      ++rep.buildingsOutsideBlocks;
    }
    BuildingOut b;
    b.shape = std::move(elements[i].shape);
    b.block = elements[i].block;
    if (chosen[i] >= 0) {
      const FloorLabel& f = parsed[static_cast<size_t>(chosen[i])];
      b.floors = f.above;
      b.floorsBelow = f.below;
      b.label = labels[static_cast<size_t>(labelIndex[static_cast<size_t>(chosen[i])])].text;
      ++rep.labelsUsed;
    }
    b.height = floorHeight(b.floors, o.groundFloorHeight, o.upperFloorHeight, o.heightOffset, o.seed,
                           result.buildings.size());
    if (b.floors > 0) ++rep.buildingsWithFloors;
    result.buildings.push_back(std::move(b));
  }
  if (!adjusted.empty()) moveVertices(result, lw.vertices, adjusted, o.minFaceArea);
  rep.buildings = result.buildings.size();
  reportProgress(progress, 1.0, "done");
  return result;
}

}  // namespace urbanvec::cadastre
