// Number-of-floors labels and heights (spec pueyo-urban-data.md §A.8). See floor_labels.hpp.
#include "urbanvec/cadastre/floor_labels.hpp"

#include <cctype>

#include "urbanvec/core/random.hpp"

namespace urbanvec::cadastre {

int romanValue(const std::string& s) {
  auto value = [](char c) {
    switch (c) {
      case 'I':
        return 1;
      case 'V':
        return 5;
      case 'X':
        return 10;
      case 'L':
        return 50;
      case 'C':
        return 100;
      case 'D':
        return 500;
      case 'M':
        return 1000;
      default:
        return -1;
    }
  };
  if (s.empty()) return -1;
  int total = 0;
  for (size_t i = 0; i < s.size(); ++i) {
    const int v = value(s[i]);
    if (v < 0) return -1;
    const int next = i + 1 < s.size() ? value(s[i + 1]) : 0;
    if (next < 0) return -1;
    total += v < next ? -v : v;
  }
  return total > 0 ? total : -1;
}

FloorLabel parseFloorLabel(const std::string& text) {
  FloorLabel out;
  std::string clean;
  for (char c : text)
    if (!std::isspace(static_cast<unsigned char>(c)))
      clean += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  size_t start = 0;
  while (start <= clean.size()) {
    size_t end = clean.find('+', start);
    if (end == std::string::npos) end = clean.size();
    std::string part = clean.substr(start, end - start);
    start = end + 1;
    if (part.empty()) continue;
    bool below = false;
    if (part[0] == '-') below = true, part = part.substr(1);
    int value = -1;
    if (!part.empty() && part.size() <= 3 && part.find_first_not_of("0123456789") == std::string::npos)
      value = std::stoi(part);
    else
      value = romanValue(part);
    if (value < 0 || value > 200) {
      ++out.ignoredParts;
      continue;
    }
    out.valid = true;
    (below ? out.below : out.above) += value;
  }
  return out;
}

double floorHeight(int floors, double ground, double upper, double maxOffset, std::uint64_t seed,
                   std::uint64_t item) {
  if (floors <= 0) return 0.0;
  double h = ground + upper * (floors - 1);
  if (maxOffset > 0.0) {
    Rng rng(deriveSeed(seed, item));
    h += std::uniform_real_distribution<double>(-maxOffset, maxOffset)(rng);
  }
  return h;
}

}  // namespace urbanvec::cadastre
