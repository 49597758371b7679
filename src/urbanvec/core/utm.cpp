#include "urbanvec/core/utm.hpp"

#include <algorithm>
#include <cmath>

namespace urbanvec {

int utmEpsgFor(double longitude, double latitude) {
  double lon = std::fmod(longitude + 180.0, 360.0);
  if (lon < 0) lon += 360.0;
  int zone = std::clamp(static_cast<int>(std::floor(lon / 6.0)) + 1, 1, 60);
  if (latitude >= 56.0 && latitude < 64.0 && longitude >= 3.0 && longitude < 12.0) zone = 32;
  if (latitude >= 72.0 && latitude < 84.0) {
    if (longitude >= 0.0 && longitude < 9.0) zone = 31;
    else if (longitude >= 9.0 && longitude < 21.0) zone = 33;
    else if (longitude >= 21.0 && longitude < 33.0) zone = 35;
    else if (longitude >= 33.0 && longitude < 42.0) zone = 37;
  }
  return (latitude >= 0.0 ? 32600 : 32700) + zone;
}

}  // namespace urbanvec
