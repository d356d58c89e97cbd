// The solver's random streams: one per (shot, element, kind, index), whatever the fields' sizes.
#include "radiosity/random_stream.h"

#include <gtest/gtest.h>

#include <unordered_set>

namespace rad {
namespace {

TEST(RandomStream, DistinctTuplesGetDistinctKeys) {
  // Element indices and patch indices in the thousands, as in a solve of the Cornell box; the
  // shift-and-xor key this replaced gave the point 4 bits, so re-gather index 8 + j collided
  // with the next elements' streams.
  std::unordered_set<uint64_t> keys;
  size_t tuples = 0;
  for (int shot = 0; shot < 4; ++shot) {
    for (int element = 0; element < 3000; ++element) {
      for (const StreamKind kind : {StreamKind::centre, StreamKind::corner, StreamKind::regather}) {
        for (int index = 0; index < (kind == StreamKind::regather ? 40 : 4); ++index) {
          keys.insert(stream_key(shot, element, kind, index));
          ++tuples;
        }
      }
    }
  }
  EXPECT_EQ(keys.size(), tuples);
  EXPECT_NE(stream_key(0, 0, StreamKind::regather, 8), stream_key(0, 1, StreamKind::centre, 0));
  EXPECT_NE(stream_key(0, 5, StreamKind::corner, 0), stream_key(0, 5, StreamKind::centre, 0));
}

TEST(RandomStream, UniformsAreInTheUnitIntervalWithTheRightMean) {
  uint64_t state = stream_key(1, 2, StreamKind::centre, 0);
  double sum = 0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    const double u = next_uniform(state);
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
  }
  // Standard error of the mean of U(0,1) over 1e5 draws: 0.0009; 5 sigma.
  EXPECT_NEAR(sum / n, 0.5, 0.0046);
}

}  // namespace
}  // namespace rad
