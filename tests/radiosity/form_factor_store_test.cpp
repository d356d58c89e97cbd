// The store of measured form factors: what was put is found (across blocks and patches), what
// was not is not (a stored zero included), and past the budget nothing is kept.
#include "radiosity/form_factor_store.h"

#include <gtest/gtest.h>

#include <vector>

namespace rad {
namespace {

constexpr size_t block = FormFactorStore::block;
constexpr size_t block_bytes = block * 3 * sizeof(float);

TEST(FormFactorStore, FindsWhatWasPutAndNothingElse) {
  FormFactorStore store(size_t(1) << 30);
  Rgb ff;
  EXPECT_FALSE(store.find(0, 0, &ff));  // nothing made yet
  const int elements = 3 * block + 5;   // several blocks, the last partly used
  store.grow(0, 3, elements);
  store.grow(2, 3, 10);
  for (int e = 0; e < elements; ++e) EXPECT_FALSE(store.find(0, e, &ff)) << e;
  store.put(0, 0, Rgb(0, 0, 0));  // a hidden pair: zero is a value, not "absent"
  store.put(0, block, Rgb(0.25, 0.5, 0.125));
  store.put(0, elements - 1, Rgb(1e-7, 2e-7, 3e-7));
  store.put(2, 9, Rgb(0.75, 0.75, 0.75));
  ASSERT_TRUE(store.find(0, 0, &ff));
  EXPECT_EQ(ff, Rgb(0, 0, 0));
  ASSERT_TRUE(store.find(0, block, &ff));
  EXPECT_EQ(ff, Rgb(0.25, 0.5, 0.125));  // exact in single precision
  ASSERT_TRUE(store.find(0, elements - 1, &ff));
  EXPECT_NEAR(ff[1], 2e-7, 2e-7 * 1e-7);  // single precision
  ASSERT_TRUE(store.find(2, 9, &ff));
  EXPECT_EQ(ff, Rgb(0.75, 0.75, 0.75));
  // Neighbours of what was put, another patch, past what was made: absent.
  EXPECT_FALSE(store.find(0, 1, &ff));
  EXPECT_FALSE(store.find(0, block - 1, &ff));
  EXPECT_FALSE(store.find(0, block + 1, &ff));
  EXPECT_FALSE(store.find(1, 0, &ff));
  EXPECT_FALSE(store.find(2, block, &ff));
  EXPECT_FALSE(store.find(0, 10 * block, &ff));
  EXPECT_FALSE(store.find(7, 0, &ff));
  store.put(1, 0, Rgb(1, 1, 1));  // no room made for patch 1: not kept
  EXPECT_FALSE(store.find(1, 0, &ff));
}

TEST(FormFactorStore, GrowingKeepsWhatWasStored) {
  FormFactorStore store(size_t(1) << 30);
  store.grow(0, 1, 10);
  store.put(0, 3, Rgb(0.5, 0.5, 0.5));
  for (int n = 11; n < 5 * static_cast<int>(block); n += static_cast<int>(block) / 3 + 1)
    store.grow(0, 1, n);
  Rgb ff;
  ASSERT_TRUE(store.find(0, 3, &ff));
  EXPECT_EQ(ff, Rgb(0.5, 0.5, 0.5));
  EXPECT_EQ(store.bytes(), 5 * block_bytes);
}

TEST(FormFactorStore, AShotThatReachesAFewReceiversStoresOnlyTheirBlocks) {
  // A floor patch's shot reaches the lamp's elements alone, at the end of the element list:
  // one block for them, not every block before them.
  FormFactorStore store(size_t(1) << 30);
  const int far = static_cast<int>(7 * block + 5);
  store.grow(0, 1, std::vector<int>{far, far + 1});
  EXPECT_EQ(store.bytes(), block_bytes);
  store.put(0, far, Rgb(0.25, 0.5, 0.75));
  store.put(0, 3, Rgb(1, 1, 1));  // no room made for the first block: not kept
  Rgb ff;
  ASSERT_TRUE(store.find(0, far, &ff));
  EXPECT_EQ(ff, Rgb(0.25, 0.5, 0.75));
  EXPECT_FALSE(store.find(0, 3, &ff));
  store.grow(0, 1, std::vector<int>{3, far});  // the first block now, the other kept
  EXPECT_EQ(store.bytes(), 2 * block_bytes);
  ASSERT_TRUE(store.find(0, far, &ff));
  EXPECT_EQ(ff, Rgb(0.25, 0.5, 0.75));
  EXPECT_FALSE(store.find(0, 3, &ff));
}

TEST(FormFactorStore, NothingIsKeptPastTheBudget) {
  FormFactorStore store(2 * block_bytes);
  store.grow(0, 2, 2 * block);  // the whole budget
  store.grow(1, 2, 10);         // none left
  EXPECT_EQ(store.bytes(), 2 * block_bytes);
  store.put(0, 2 * block - 1, Rgb(0.5, 0.5, 0.5));
  store.put(1, 0, Rgb(0.5, 0.5, 0.5));
  Rgb ff;
  EXPECT_TRUE(store.find(0, 2 * block - 1, &ff));
  EXPECT_FALSE(store.find(1, 0, &ff));
  store.grow(0, 2, 3 * block);  // a third block would pass the budget
  EXPECT_FALSE(store.find(0, 2 * block, &ff));
  EXPECT_EQ(store.bytes(), 2 * block_bytes);
}

}  // namespace
}  // namespace rad
