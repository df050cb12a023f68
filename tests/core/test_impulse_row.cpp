// The warm start's row format (cd::impulse_row): what is appended is found by its partner, a
// missing partner carries nothing, a full row refuses more, and the row's used width is what a
// host copies.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "cd/impulse_row.h"

namespace {

namespace row = cd::impulse_row;

TEST(ImpulseRow, FindsWhatWasAppendedByPartner)
{
  std::vector<double> storage(row::width(3), -1.0);
  double* r = storage.data();
  row::clear(r);
  EXPECT_EQ(row::used(r), 1);
  ASSERT_TRUE(row::append(r, 3, 7, {0.5, -0.25}));
  ASSERT_TRUE(row::append(r, 3, 2, {1.5, 0.75}));
  EXPECT_EQ(row::entries(r), 2);
  EXPECT_EQ(row::used(r), 7);
  EXPECT_EQ(row::find(r, 2).n, 1.5);
  EXPECT_EQ(row::find(r, 2).t, 0.75);
  EXPECT_EQ(row::find(r, 7).n, 0.5);
  EXPECT_EQ(row::find(r, 7).t, -0.25);
  const cd::Local2 none = row::find(r, 3);
  EXPECT_EQ(none.n, 0.0);
  EXPECT_EQ(none.t, 0.0);
}

TEST(ImpulseRow, AFullRowRefusesAndKeepsItsEntries)
{
  std::vector<double> storage(row::width(1));
  double* r = storage.data();
  row::clear(r);
  ASSERT_TRUE(row::append(r, 1, 4, {1.0, 0.0}));
  EXPECT_FALSE(row::append(r, 1, 5, {2.0, 0.0}));
  EXPECT_EQ(row::entries(r), 1);
  EXPECT_EQ(row::find(r, 4).n, 1.0);
  EXPECT_EQ(row::find(r, 5).n, 0.0);
  row::clear(r);
  EXPECT_EQ(row::find(r, 4).n, 0.0) << "a cleared row carries nothing";
}

// Partners are ids, stored among doubles: ids next to each other up to 2^53, and the negative
// ids of walls, are told apart.
TEST(ImpulseRow, TellsLargeAndNegativeIdsApart)
{
  std::vector<double> storage(row::width(4));
  double* r = storage.data();
  row::clear(r);
  const std::int64_t largest = (std::int64_t{1} << 53) - 1;
  ASSERT_TRUE(row::append(r, 4, largest, {1.0, 0.0}));
  ASSERT_TRUE(row::append(r, 4, largest - 1, {2.0, 0.0}));
  ASSERT_TRUE(row::append(r, 4, -1, {3.0, 0.0}));
  ASSERT_TRUE(row::append(r, 4, -2, {4.0, 0.0}));
  EXPECT_EQ(row::find(r, largest).n, 1.0);
  EXPECT_EQ(row::find(r, largest - 1).n, 2.0);
  EXPECT_EQ(row::find(r, -1).n, 3.0);
  EXPECT_EQ(row::find(r, -2).n, 4.0);
  EXPECT_EQ(row::find(r, 1).n, 0.0);
}

}  // namespace
