#include <gtest/gtest.h>

#include "analysis/independent_rows.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

// Claim: detail::independent_rows keeps exactly the rows that raise the rank of what comes before
// them. Ranks by hand: with body 0 pinned (before), the row v_0 = 0 repeats the pin; v_0 − v_1 = 0 is
// new (rank 2); v_1 = 0 then follows from the two (v_1 = v_0 = 0); 2 v_2 − v_3 = 0 is new (rank 3),
// and 4 v_2 − 2 v_3 = 0 is the same row doubled.
TEST(IndependentRows, KeepsTheRowsThatRaiseTheRank) {
  const ConstraintRows before = {{{0, 1.0}}};
  const ConstraintRows rows = {{{0, 1.0}}, {{0, 1.0}, {1, -1.0}}, {{1, 1.0}}, {{2, 2.0}, {3, -1.0}}, {{2, 4.0}, {3, -2.0}}};
  EXPECT_EQ(detail::independent_rows(before, rows), (std::vector<size_t>{1, 3}));
  // Without the pin the first row is new too, and v_1 = 0 still follows (from rows 0 and 1).
  EXPECT_EQ(detail::independent_rows({}, rows), (std::vector<size_t>{0, 1, 3}));
  EXPECT_TRUE(detail::independent_rows(before, {}).empty());
}

}  // namespace
}  // namespace machdyn
