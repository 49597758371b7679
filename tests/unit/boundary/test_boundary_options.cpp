// Options of the generator that are not finite are refused (issue 15), not carried into the output.
#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "urbanvec/boundary/generate_boundary.hpp"
#include "urbanvec/core/error.hpp"

namespace urbanvec::boundary {
namespace {

std::string message(const BoundaryOptions& options) {
  try {
    generateBoundary(options);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::InvalidOption);
    return e.what();
  }
  return "(no error)";
}

TEST(BoundaryOptions, NonFiniteSuburbAreaOrSlopeIsRefused) {
  BoundaryOptions options;
  options.noise.size = 32;
  options.noise.startLayer = 1;
  options.noise.endLayer = 5;
  options.suburbMinimumPixels = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(message(options),
            "the minimum suburb area (-suburbs) must be a finite number >= 0, got nan pixels");
  options.suburbMinimumPixels = -1;
  EXPECT_EQ(message(options),
            "the minimum suburb area (-suburbs) must be a finite number >= 0, got -1.000000 pixels");
  options.suburbMinimumPixels = 0;
  options.transform.slopeExponent = std::numeric_limits<double>::infinity();
  EXPECT_EQ(message(options), "the slope exponent n (-slope) must be positive, got inf");
}

}  // namespace
}  // namespace urbanvec::boundary
