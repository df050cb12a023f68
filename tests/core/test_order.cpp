// cd::interleaved_order: the sweep order that keeps contacts sharing a body a few places apart.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include "cd/order.h"

namespace {

std::vector<cd::Contact> contacts_between(const std::vector<std::pair<int, int>>& bodies)
{
  std::vector<cd::Contact> contacts;
  for (const auto& [a, b] : bodies) {
    cd::Contact c;
    c.body_a = a;
    c.body_b = b;
    contacts.push_back(c);
  }
  return contacts;
}

TEST(InterleavedOrder, ALaterContactFillsTheGapAndTheWaitingOneFollows)
{
  // A and B share body 1; C shares nothing: A, C, then B two slots after A.
  const auto contacts = contacts_between({{1, 2}, {1, 3}, {4, 5}});
  EXPECT_EQ(cd::interleaved_order(contacts, 6, 2), (std::vector<int>{0, 2, 1}));
}

TEST(InterleavedOrder, WithNothingToFillTheGapTheOldestWaitingContactGoesNext)
{
  const auto contacts = contacts_between({{1, 2}, {1, 3}, {2, 3}});
  EXPECT_EQ(cd::interleaved_order(contacts, 4, 4), (std::vector<int>{0, 1, 2}));
}

TEST(InterleavedOrder, HubsTakeTurnsAndEveryContactComesOnce)
{
  // Hub h (body 1 + h) touches two leaves, its contacts listed together: the hubs take turns,
  // so the two contacts of a hub end up at least the spacing of 4 apart.
  std::vector<std::pair<int, int>> bodies;
  for (int hub = 0; hub < 8; hub++)
    for (int leaf = 0; leaf < 2; leaf++) bodies.emplace_back(1 + hub, 9 + 2 * hub + leaf);
  const auto contacts = contacts_between(bodies);
  const std::vector<int> order = cd::interleaved_order(contacts, 9 + 16, 4);

  std::vector<int> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  std::vector<int> every(contacts.size());
  std::iota(every.begin(), every.end(), 0);
  EXPECT_EQ(sorted, every);
  for (std::size_t slot = 1; slot < order.size(); slot++)
    for (std::size_t earlier = slot < 3 ? 0 : slot - 3; earlier < slot; earlier++)
      EXPECT_NE(contacts[order[slot]].body_a, contacts[order[earlier]].body_a) << "slots " << earlier << ", " << slot;
}

TEST(InterleavedOrder, ARandomContactListComesBackPermuted)
{
  std::mt19937 random(7);
  std::vector<std::pair<int, int>> bodies;
  for (int k = 0; k < 5000; k++) {
    const int a = 1 + static_cast<int>(random() % 2000);
    bodies.emplace_back(a, random() % 10 == 0 ? 0 : a + 1 + static_cast<int>(random() % 50));
  }
  const auto contacts = contacts_between(bodies);
  std::vector<int> order = cd::interleaved_order(contacts, 2100);
  std::sort(order.begin(), order.end());
  for (std::size_t k = 0; k < order.size(); k++) ASSERT_EQ(order[k], static_cast<int>(k));
}

}  // namespace
