// The order of a sweep: which contact the Gauss–Seidel sweep visits after which. The solution
// a sweep converges to does not depend on it; how fast it gets there, and at what cost per
// update, does (doc/benchmarks.md).
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "cd/contact.h"

namespace cd {

// The sweep order of a step: interleaved (interleaved_order), shuffled (seeded: shuffled_order),
// or as the host offered the pairs (a benchmark's baseline).
enum class ContactOrder { interleaved, shuffled, as_offered };

// A permutation of the contacts in their order, except that contacts sharing a body are kept
// at least `spacing` places apart where a nearby contact can fill the gap: an update then never
// waits for the store of the previous update of the same body (the gain: doc/benchmarks.md).
std::vector<int> interleaved_order(const std::vector<Contact>& contacts, int body_count, int spacing = 4);

// A uniformly random permutation of `count` contacts (Fisher–Yates, drawn from `rng`), into
// `permutation`.
void shuffled_order(std::size_t count, std::mt19937_64& rng, std::vector<int>& permutation);

}  // namespace cd
