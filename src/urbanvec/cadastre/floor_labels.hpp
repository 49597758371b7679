// Number-of-floors labels and heights (spec pueyo-urban-data.md §A.8).
#pragma once

#include <cstdint>
#include <string>

namespace urbanvec::cadastre {

/// A parsed floor label. The rule (docs/cadastre.md): the text is split at '+'; a part made of Roman
/// numerals (I V X L C D M) or Arabic digits counts floors above ground, the same with a leading '-'
/// counts floors below ground (`-I+III`: 1 below, 3 above); parts are summed; any other part (`TZA`,
/// `POR`, ... the cadastre's use codes) is ignored and counted. A label with no numeric part is not a
/// number.
struct FloorLabel {
  bool valid = false;
  int above = 0;
  int below = 0;
  int ignoredParts = 0;
};

FloorLabel parseFloorLabel(const std::string& text);
/// Value of a Roman numeral (upper case, subtractive notation), or -1 when it is not one.
int romanValue(const std::string& s);

/// h = ground + upper (floors - 1) + offset for floors >= 1, 0 for 0 floors (a courtyard, §A.8); the
/// offset is uniform in [-maxOffset, maxOffset], drawn from (seed, item) so it is reproducible.
double floorHeight(int floors, double ground, double upper, double maxOffset, std::uint64_t seed,
                   std::uint64_t item);

}  // namespace urbanvec::cadastre
