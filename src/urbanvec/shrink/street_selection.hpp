// Step 2 of the shrinking pipeline (spec §B.4): importance weight impW and density impD of every
// street, and the selection of the top shF fraction.
#pragma once

#include <vector>

#include "urbanvec/shrink/city.hpp"
#include "urbanvec/shrink/indirect_streets.hpp"
#include "urbanvec/shrink/shrink_options.hpp"
#include "urbanvec/shrink/street_graph.hpp"

namespace urbanvec::shrink {

struct StreetScore {
  double impW = 0.0;      ///< [0.05, 1]
  double length = 0.0;    ///< metres
  double impD = 0.0;      ///< impW / length, per metre
  int intersections = 0;  ///< nInt: nodes shared with another street
};

struct Selection {
  std::vector<StreetScore> scores;  ///< per street
  std::vector<char> selected;       ///< per street
  int selectedCount = 0;
  int importantCount = 0;  ///< streets with a place weight
  int importantSelected = 0;
};

/// strT of a highway value: its highwayWeights entry / 10 (§B.4).
double streetTypeWeight(const std::string& highway, const SelectionOptions& options);

/// impW = importantBase + (1 - importantBase) appearW for important streets, else
/// strT + 0.1 nInt/nInt_M + 0.1 (len - len_m)/(len_M - len_m); sorts by impW (ties: important first,
/// then street order) and selects exactly round(shF * #streets) streets (§H.2 item 2).
Selection selectStreets(const City& city, const StreetGraph& graph,
                        const std::vector<StreetImportance>& importance, const SelectionOptions& options);

}  // namespace urbanvec::shrink
