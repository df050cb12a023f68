#include "cd/order.h"

#include <utility>

namespace cd {

std::vector<int> interleaved_order(const std::vector<Contact>& contacts, int body_count, int spacing)
{
  // Greedy: each slot takes the first waiting contact whose bodies were last used at least
  // `spacing` slots ago, looking a bounded distance ahead; otherwise the oldest waiting one.
  // The waiting contacts form a list in their order (after_[k]: the next one waiting after k),
  // so that taking one from the middle costs nothing.
  constexpr int lookahead = 16;
  const int count = static_cast<int>(contacts.size());
  const int end = count;  // after_[end] is the first waiting contact
  std::vector<int> after(count + 1);
  for (int k = 0; k < count; k++) after[k] = k + 1;
  after[end] = 0;
  std::vector<int> last_slot(body_count, -spacing);
  std::vector<int> order;
  order.reserve(contacts.size());
  for (int slot = 0; slot < count; slot++) {
    int before_chosen = end;  // the waiting contact before the chosen one (end: none)
    for (int before = end, seen = 0; after[before] != end && seen < lookahead; before = after[before], seen++) {
      const Contact& c = contacts[after[before]];
      if (slot - last_slot[c.body_a] >= spacing && slot - last_slot[c.body_b] >= spacing) {
        before_chosen = before;
        break;
      }
    }
    const int chosen = after[before_chosen];
    after[before_chosen] = after[chosen];
    last_slot[contacts[chosen].body_a] = last_slot[contacts[chosen].body_b] = slot;
    order.push_back(chosen);
  }
  return order;
}

void shuffled_order(std::size_t count, std::mt19937_64& rng, std::vector<int>& permutation)
{
  permutation.resize(count);
  for (std::size_t k = 0; k < permutation.size(); k++) permutation[k] = static_cast<int>(k);
  for (std::size_t k = permutation.size(); k > 1; k--) {
    std::uniform_int_distribution<std::size_t> pick(0, k - 1);
    std::swap(permutation[k - 1], permutation[pick(rng)]);
  }
}

}  // namespace cd
