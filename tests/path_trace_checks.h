#pragma once
/// Judging a path-traced estimate against an expected value (tests of the path tracer).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "reference/path_tracer.h"

namespace rad::test {

/// |mean - expected| <= 4 standard errors + `slack` per channel (slack: what the expected value
/// itself may be off by, a finite source standing for an infinite one), and the standard error
/// below `precision` relative, so that the check means something.
inline ::testing::AssertionResult within(const PathTraceEstimate& e, const Rgb& expected,
                                         double precision, double slack = 1e-12) {
  for (int c = 0; c < 3; ++c) {
    const double tolerance = 4 * e.standard_error[c] + slack;
    if (!(std::abs(e.mean[c] - expected[c]) <= tolerance) ||
        !(e.standard_error[c] <= precision * std::max(expected[c], 1e-12))) {
      return ::testing::AssertionFailure() << "channel " << c << ": " << e.mean[c] << " +- "
                                           << e.standard_error[c] << ", expected " << expected[c];
    }
  }
  return ::testing::AssertionSuccess();
}

}  // namespace rad::test
