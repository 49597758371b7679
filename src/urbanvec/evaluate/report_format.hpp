// How an evaluation is shown (issue 2 §3): the table printed by `urbanvec evaluate` and its JSON
// report. Absent metrics print as `absent` in the table and `null` in JSON, never as 0.
#pragma once

#include <string>

#include "urbanvec/evaluate/evaluate.hpp"

namespace urbanvec::evaluate {

/// Where each layer came from, for the header of the table and the "layers" object of the JSON.
struct ReportInputs {
  std::string result;  ///< path of the result dataset
  std::string truth;   ///< path of the truth dataset
  /// Description of each layer read ("'roads' of 'result.gpkg'"); empty when the layer is absent.
  std::string resultRoads, resultBlocks, resultParcels;
  std::string truthRoads, truthBlocks, truthParcels;
};

/// "x <min> to <max>, y <min> to <max>", for messages.
std::string formatExtent(const Extent& extent);

/// The human-readable table: one metric per line, name column padded, ending with a newline.
std::string formatReportTable(const EvaluationReport& report, const ReportInputs& inputs);

/// The JSON document (pretty-printed, two-space indent, ending with a newline).
std::string formatReportJson(const EvaluationReport& report, const ReportInputs& inputs);

}  // namespace urbanvec::evaluate
