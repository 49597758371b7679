// The skeleton city (spec §B.7): the selected, connecting and dead-end ways plus the important
// non-street places, as the steps of §B.5–§B.7 build it.
#pragma once

#include <vector>

#include "urbanvec/shrink/city.hpp"

namespace urbanvec::shrink {

enum class WayKind {
  Important,        ///< a street with a place weight (member or indirect, §B.3)
  Selected,         ///< kept by shF (§B.4)
  Connector,        ///< added to join clusters (§B.5)
  DeadEndConnector  ///< new way joining a dead end (§B.6)
};
const char* wayKindName(WayKind kind);

struct SkeletonWay {
  CityWay way;      ///< for a dead-end connector: a brand-new negative id (§B.6)
  int street = -1;  ///< index into City::streets, -1 for a new way
  double impW = 0.0;
  WayKind kind = WayKind::Selected;
  int place = -1;  ///< the place that made it important, -1 for none
};

struct Skeleton {
  std::vector<SkeletonWay> ways;
  std::vector<int> places;  ///< indices of the places whose non-street elements it holds (§B.7)
};

}  // namespace urbanvec::shrink
