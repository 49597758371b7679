// How an evaluation is shown (issue 2 §3): see report_format.hpp.
#include "urbanvec/evaluate/report_format.hpp"

#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>
#include <utility>
#include <vector>

namespace urbanvec::evaluate {

namespace {

constexpr const char* kAbsent = "absent";

std::string format(const char* pattern, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

std::string count(const std::optional<std::size_t>& n) {
  return n ? std::to_string(*n) : kAbsent;
}

std::string number(const std::optional<double>& v, const char* pattern) {
  return v ? format(pattern, *v) : kAbsent;
}

std::string distanceRow(const std::optional<DistanceSummary>& d, bool p95) {
  if (!d) return kAbsent;
  return format("%.2f m", p95 ? d->p95Metres : d->medianMetres) + " = " +
         format("%.3f cells", p95 ? d->p95Cells : d->medianCells);
}

template <class T>
nlohmann::ordered_json orNull(const std::optional<T>& v) {
  return v ? nlohmann::ordered_json(*v) : nlohmann::ordered_json();
}

nlohmann::ordered_json orNull(const std::string& s) {
  return s.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(s);
}

nlohmann::ordered_json distanceJson(const std::optional<DistanceSummary>& d) {
  if (!d) return nlohmann::ordered_json();
  nlohmann::ordered_json j;
  j["samples"] = d->samples;
  j["median_m"] = d->medianMetres;
  j["p95_m"] = d->p95Metres;
  j["median_cells"] = d->medianCells;
  j["p95_cells"] = d->p95Cells;
  return j;
}

nlohmann::ordered_json extentJson(const std::optional<Extent>& e) {
  if (!e) return nlohmann::ordered_json();
  nlohmann::ordered_json j;
  j["min_x"] = e->minX;
  j["min_y"] = e->minY;
  j["max_x"] = e->maxX;
  j["max_y"] = e->maxY;
  return j;
}

}  // namespace

std::string formatExtent(const Extent& e) {
  return "x " + format("%.10g", e.minX) + " to " + format("%.10g", e.maxX) + ", y " +
         format("%.10g", e.minY) + " to " + format("%.10g", e.maxY);
}

std::string formatReportTable(const EvaluationReport& report, const ReportInputs& inputs) {
  const RoadReport& r = report.roads;
  const BlockReport& b = report.blocks;
  const ParcelReport& p = report.parcels;
  std::vector<std::pair<std::string, std::string>> rows;
  auto layer = [](const std::string& s) { return s.empty() ? std::string(kAbsent) : s; };
  rows.push_back({"result roads", layer(inputs.resultRoads)});
  rows.push_back({"result blocks", layer(inputs.resultBlocks)});
  rows.push_back({"result parcels", layer(inputs.resultParcels)});
  rows.push_back({"truth roads", layer(inputs.truthRoads)});
  rows.push_back({"truth blocks", layer(inputs.truthBlocks)});
  rows.push_back({"truth parcels", layer(inputs.truthParcels)});
  rows.push_back({"cell size", format("%g m", report.cellSize)});
  rows.push_back({"", ""});
  rows.push_back({"roads: lines truth / result", count(r.truthLines) + " / " + count(r.resultLines)});
  rows.push_back({"roads: length truth / result",
                  number(r.truthLengthKm, "%.3f km") + " / " + number(r.resultLengthKm, "%.3f km")});
  rows.push_back({"roads: distance truth->result median", distanceRow(r.truthToResult, false)});
  rows.push_back({"roads: distance truth->result p95", distanceRow(r.truthToResult, true)});
  rows.push_back({"roads: distance result->truth median", distanceRow(r.resultToTruth, false)});
  rows.push_back({"roads: distance result->truth p95", distanceRow(r.resultToTruth, true)});
  rows.push_back({"roads: turning truth", number(r.truthTurningPerKm, "%.1f deg/km")});
  rows.push_back({"roads: turning result", number(r.resultTurningPerKm, "%.1f deg/km")});
  std::string ratio = number(r.turningRatio, "%.3f");
  if (!r.turningRatio && r.truthTurningPerKm && r.resultTurningPerKm)
    ratio = "undefined (the truth roads never turn)";
  rows.push_back({"roads: turning ratio result/truth", ratio});
  if (r.truthTurningByBend || r.resultTurningByBend) {
    for (std::size_t i = 0; i <= r.bendClassEdges.size(); ++i) {
      const std::string from = i == 0 ? "0" : format("%g", r.bendClassEdges[i - 1]);
      const std::string label =
          i == r.bendClassEdges.size() ? ">=" + from : from + "-" + format("%g", r.bendClassEdges[i]);
      auto side = [&](const std::optional<std::vector<double>>& v) {
        return v ? format("%.1f", (*v)[i]) : std::string(kAbsent);
      };
      rows.push_back({"roads: turning " + label + " deg truth/result",
                      side(r.truthTurningByBend) + " / " + side(r.resultTurningByBend) + " deg/km"});
    }
    rows.push_back({"roads: turning ratio bends >=" + format("%g", r.sharpBendDegrees) + " deg",
                    number(r.sharpTurningRatio, "%.3f")});
  }
  auto network = [](const std::optional<NetworkSummary>& n) {
    if (!n) return std::string("absent");
    char text[96];
    std::snprintf(text, sizeof text, "%zu intersections, %zu dead ends, %zu components", n->intersections,
                  n->deadEnds, n->components);
    return std::string(text);
  };
  rows.push_back({"roads: network truth", network(r.truthNetwork)});
  rows.push_back({"roads: network result", network(r.resultNetwork)});
  rows.push_back({"blocks: count truth / result", count(b.truthCount) + " / " + count(b.resultCount)});
  if (b.truthSmallCount)
    rows.push_back({"blocks: truth < " + format("%g", b.minTruthBlockCells) + " cells, not counted",
                    count(b.truthSmallCount)});
  std::string matched = number(b.matchedShare, "%.4f");
  if (b.matchedShare)
    matched += " (" + std::to_string(*b.matchedCount) + " of " + std::to_string(*b.truthCount) + ")";
  rows.push_back({"blocks: matched share (IoU >= " + format("%g", b.iouThreshold) + ")", matched});
  if (b.internalTruthCount) {
    std::string internal = number(b.internalMatchedShare, "%.4f");
    if (b.internalMatchedShare)
      internal += " (" + std::to_string(*b.internalMatchedCount) + " of " +
                  std::to_string(*b.internalTruthCount) + ")";
    rows.push_back({"blocks: matched share, internal", internal});
  }
  if (b.matchableTruthCount) {
    std::string matchable = number(b.matchableMatchedShare, "%.4f");
    if (b.matchableMatchedShare)
      matchable += " (" + std::to_string(*b.matchableMatchedCount) + " of " +
                   std::to_string(*b.matchableTruthCount) + " with >= " + format("%g", b.matchableLandShare) +
                   " of their area on land)";
    rows.push_back({"blocks: matched share, matchable", matchable});
  }
  rows.push_back({"blocks: mean best IoU", number(b.meanBestIoU, "%.4f")});
  rows.push_back({"blocks: invalid result geometries", count(b.resultInvalidCount)});
  rows.push_back({"parcels: count truth / result", count(p.truthCount) + " / " + count(p.resultCount)});
  std::string ratios = kAbsent;
  if (p.countRatioMean)
    ratios = "mean " + format("%.3f", *p.countRatioMean) + ", median " + format("%.3f", *p.countRatioMedian) +
             " (" + std::to_string(*p.comparedBlocks) + " blocks)";
  rows.push_back({"parcels: count ratio per matched block", ratios});
  rows.push_back({"parcels: land-use share error (L1)", number(p.landUseErrorMean, "%.4f")});
  rows.push_back({"parcels: gap share", number(p.gapShare, "%.4f")});
  rows.push_back({"parcels: overlap share", number(p.overlapShare, "%.4f")});
  std::string invalid = number(p.invalidShare, "%.4f");
  if (p.invalidShare)
    invalid += " (" + std::to_string(*p.invalidCount) + " of " + std::to_string(*p.resultCount) + ")";
  rows.push_back({"parcels: invalid geometries", invalid});

  std::size_t width = 0;
  for (const auto& [name, value] : rows) width = std::max(width, name.size());
  std::ostringstream out;
  for (const auto& [name, value] : rows) {
    if (name.empty()) {
      out << "\n";
      continue;
    }
    out << name << std::string(width + 2 - name.size(), ' ') << value << "\n";
  }
  return out.str();
}

std::string formatReportJson(const EvaluationReport& report, const ReportInputs& inputs) {
  const RoadReport& r = report.roads;
  const BlockReport& b = report.blocks;
  const ParcelReport& p = report.parcels;
  nlohmann::ordered_json j;
  j["result"] = inputs.result;
  j["truth"] = inputs.truth;
  j["cell_size_m"] = report.cellSize;
  j["layers"] = {
      {"result_roads", orNull(inputs.resultRoads)},     {"result_blocks", orNull(inputs.resultBlocks)},
      {"result_parcels", orNull(inputs.resultParcels)}, {"truth_roads", orNull(inputs.truthRoads)},
      {"truth_blocks", orNull(inputs.truthBlocks)},     {"truth_parcels", orNull(inputs.truthParcels)}};
  j["extent"] = {{"result", extentJson(report.resultExtent)},
                 {"truth", extentJson(report.truthExtent)},
                 {"overlap", report.layersOverlap}};
  nlohmann::ordered_json roads;
  roads["truth_lines"] = orNull(r.truthLines);
  roads["result_lines"] = orNull(r.resultLines);
  roads["truth_length_km"] = orNull(r.truthLengthKm);
  roads["result_length_km"] = orNull(r.resultLengthKm);
  roads["distance_truth_to_result"] = distanceJson(r.truthToResult);
  roads["distance_result_to_truth"] = distanceJson(r.resultToTruth);
  roads["truth_turning_deg_per_km"] = orNull(r.truthTurningPerKm);
  roads["result_turning_deg_per_km"] = orNull(r.resultTurningPerKm);
  roads["turning_ratio"] = orNull(r.turningRatio);
  roads["bend_class_edges_deg"] = r.bendClassEdges;
  roads["truth_turning_by_bend_deg_per_km"] = orNull(r.truthTurningByBend);
  roads["result_turning_by_bend_deg_per_km"] = orNull(r.resultTurningByBend);
  roads["sharp_bend_deg"] = r.sharpBendDegrees;
  roads["truth_sharp_turning_deg_per_km"] = orNull(r.truthSharpTurningPerKm);
  roads["result_sharp_turning_deg_per_km"] = orNull(r.resultSharpTurningPerKm);
  roads["sharp_turning_ratio"] = orNull(r.sharpTurningRatio);
  auto networkJson = [](const std::optional<NetworkSummary>& n) {
    if (!n) return nlohmann::ordered_json();
    nlohmann::ordered_json out;
    out["intersections"] = n->intersections;
    out["dead_ends"] = n->deadEnds;
    out["components"] = n->components;
    return out;
  };
  roads["truth_network"] = networkJson(r.truthNetwork);
  roads["result_network"] = networkJson(r.resultNetwork);
  j["roads"] = roads;
  nlohmann::ordered_json blocks;
  blocks["truth_count"] = orNull(b.truthCount);
  blocks["result_count"] = orNull(b.resultCount);
  blocks["truth_small_count"] = orNull(b.truthSmallCount);
  blocks["min_truth_block_cells"] = b.minTruthBlockCells;
  blocks["iou_threshold"] = b.iouThreshold;
  blocks["matched_count"] = orNull(b.matchedCount);
  blocks["matched_share"] = orNull(b.matchedShare);
  blocks["internal_truth_count"] = orNull(b.internalTruthCount);
  blocks["internal_matched_count"] = orNull(b.internalMatchedCount);
  blocks["internal_matched_share"] = orNull(b.internalMatchedShare);
  blocks["matchable_land_share"] = b.matchableLandShare;
  blocks["matchable_truth_count"] = orNull(b.matchableTruthCount);
  blocks["matchable_matched_count"] = orNull(b.matchableMatchedCount);
  blocks["matchable_matched_share"] = orNull(b.matchableMatchedShare);
  blocks["mean_best_iou"] = orNull(b.meanBestIoU);
  blocks["result_invalid_count"] = orNull(b.resultInvalidCount);
  j["blocks"] = blocks;
  nlohmann::ordered_json parcels;
  parcels["truth_count"] = orNull(p.truthCount);
  parcels["result_count"] = orNull(p.resultCount);
  parcels["compared_blocks"] = orNull(p.comparedBlocks);
  parcels["count_ratio_mean"] = orNull(p.countRatioMean);
  parcels["count_ratio_median"] = orNull(p.countRatioMedian);
  parcels["landuse_share_error_mean"] = orNull(p.landUseErrorMean);
  parcels["gap_share"] = orNull(p.gapShare);
  parcels["overlap_share"] = orNull(p.overlapShare);
  parcels["invalid_count"] = orNull(p.invalidCount);
  parcels["invalid_share"] = orNull(p.invalidShare);
  j["parcels"] = parcels;
  return j.dump(2) + "\n";
}

}  // namespace urbanvec::evaluate
