// What bounds a solve (bench/peers/solve_limits.h): W's factor and rank against closed-form
// counts on known geometries and against the committed sample's W, the directions an answer's
// impulses are free in, and the fit of a convergence trace.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "local_problem.h"
#include "solve_limits.h"

namespace {

const std::string data = std::string(CD_TEST_DATA) + "/peers/";

constexpr double radius = 0.5;  // m
constexpr double mass = 2.0;    // kg

// The contact of disk a (body index, > 0) with disk b (0: the world), normal from b to a.
cd::Contact disk_contact(int a, int b, double normal_x, double normal_y)
{
  const double inv_inertia = 1.0 / (0.5 * mass * radius * radius);
  cd::Contact c;
  c.body_a = a;
  c.body_b = b;
  c.normal_x = normal_x;
  c.normal_y = normal_y;
  c.lever_a = radius;
  c.inv_mass_a = 1.0 / mass;
  c.spin_gain_a = radius * inv_inertia;
  if (b > 0) {
    c.lever_b = radius;
    c.inv_mass_b = 1.0 / mass;
    c.spin_gain_b = radius * inv_inertia;
  }
  return c;
}

// n disks in a row, each touching the next; on the floor (the world) or free.
std::vector<cd::Contact> row_of_disks(int n, bool on_floor)
{
  std::vector<cd::Contact> contacts;
  for (int i = 1; i <= n; i++) {
    if (on_floor) contacts.push_back(disk_contact(i, 0, 0.0, 1.0));
    if (i < n) contacts.push_back(disk_contact(i + 1, i, 1.0, 0.0));
  }
  return contacts;
}

// A local problem of `contacts` contacts with friction mu, for the states and directions.
peers::LocalProblem problem_of(int contacts, double mu)
{
  peers::LocalProblem local;
  local.contacts = contacts;
  local.mu.assign(contacts, mu);
  return local;
}

TEST(PeerLimits, AFreeChainOfDisksIsFullRank)
{
  // A chain is a tree: each contact's two constraints are new, W (2(n-1) rows) is nonsingular.
  for (const int n : {2, 5, 12}) {
    const peers::Mobility b = peers::mobility(row_of_disks(n, false), 1.0);
    EXPECT_EQ(b.grains, n);
    const peers::Spectrum w = peers::gram_spectrum(b.factor);
    EXPECT_EQ(w.rows, 2 * (n - 1));
    EXPECT_EQ(w.rank, 2 * (n - 1)) << n << " disks";
    EXPECT_EQ(w.null_dimension, 0);
  }
}

TEST(PeerLimits, DisksOnAFloorHaveRankThreePerGrain)
{
  // n disks on the floor, touching in a row: 2n - 1 contacts, 4n - 2 unknowns; no motion keeps
  // every contact closed and rolling (rolling on the floor turns neighbours the same way, their
  // contact would slip), so W's rank is every grain's 3 and its null space n - 2.
  for (const int n : {3, 6, 10}) {
    const std::vector<cd::Contact> contacts = row_of_disks(n, true);
    const peers::Mobility b = peers::mobility(contacts, 1.0);
    const peers::Spectrum w = peers::gram_spectrum(b.factor);
    EXPECT_EQ(w.rows, 4 * n - 2);
    EXPECT_EQ(w.rank, 3 * n) << n << " disks";
    EXPECT_EQ(w.null_dimension, n - 2);
    EXPECT_EQ(peers::sparse_rank(b.factor), 3 * n);
    EXPECT_LT(w.largest_zero, 1e-12 * w.largest);
    EXPECT_GT(w.range_condition(), 1e-4);  // the cut falls in a wide gap

    // Every contact sticking: the impulses may move in all 4n - 2 directions, n - 2 of them
    // leave u unchanged (statically indeterminate). Every contact sliding: one direction each,
    // the edge of its cone; 2n - 1 of them against 3n degrees of freedom, none free.
    const peers::LocalProblem local = problem_of(static_cast<int>(contacts.size()), 0.5);
    for (const bool sliding : {false, true}) {
      std::vector<double> reaction;
      for (std::size_t i = 0; i < contacts.size(); i++) {
        reaction.push_back(1.0);
        reaction.push_back(sliding ? -0.5 : 0.1);
      }
      const std::vector<peers::State> states = peers::contact_states(local, reaction, 1e-6);
      for (const peers::State s : states) EXPECT_EQ(s, sliding ? peers::State::slide : peers::State::stick);
      const peers::SparseMatrix faces =
          peers::SparseMatrix(b.factor.transpose()) * peers::free_directions(local, reaction, states);
      const peers::Spectrum f = peers::gram_spectrum(peers::SparseMatrix(peers::unit_diagonal(faces).transpose()));
      EXPECT_EQ(f.rows, sliding ? 2 * n - 1 : 4 * n - 2);
      EXPECT_EQ(f.null_dimension, sliding ? 0 : n - 2) << n << " disks, sliding " << sliding;
    }

    // An open contact drops out of the active block: the first floor contact open leaves
    // 4n - 4 active rows of rank 3n (n > 3: still indeterminate) or one fewer.
    std::vector<double> reaction(2 * contacts.size(), 0.0);
    for (std::size_t i = 1; i < contacts.size(); i++) reaction[2 * i] = 1.0;
    const std::vector<peers::State> states = peers::contact_states(local, reaction, 1e-6);
    EXPECT_EQ(states[0], peers::State::open);
    const peers::Spectrum active = peers::gram_spectrum(peers::active_rows(b.factor, states));
    EXPECT_EQ(active.rows, 4 * n - 4);
    EXPECT_EQ(active.rank + active.null_dimension, 4 * n - 4);
  }
}

TEST(PeerLimits, TheFactorRebuildsTheSamplesW)
{
  for (const char* sample : {"chute_mu2_step", "stall_mu2_e0.5_hard"}) {
    const peers::LocalProblem local = peers::read_fclib(data + sample + ".hdf5");
    const peers::Mobility b = peers::mobility(cd::read_problem(data + sample + ".cdp").contacts, local.impulse_scale);
    EXPECT_LT(peers::factor_mismatch(b, local), 1e-12) << sample;
    const peers::Spectrum w = peers::gram_spectrum(b.factor);
    EXPECT_EQ(w.rows, local.size());
    EXPECT_LE(w.rank, 3 * b.grains) << sample;
    EXPECT_GT(w.rank, 0);
    EXPECT_LT(w.largest_zero, 1e-6 * w.smallest_nonzero) << sample << ": no gap at the cut";
    // The sparse QR's rank, used where the Gram matrix is too large to be dense, agrees.
    EXPECT_EQ(peers::sparse_rank(b.factor), w.rank) << sample;
    const peers::Spectrum by_qr = peers::gram_spectrum(b.factor, 100);
    EXPECT_EQ(by_qr.rank, w.rank);
    EXPECT_TRUE(std::isnan(by_qr.largest));
  }
}

TEST(PeerLimits, AFactorOfAnotherScaleIsRefused)
{
  const peers::LocalProblem local = peers::read_fclib(data + "chute_mu2_step.hdf5");
  const peers::Mobility b =
      peers::mobility(cd::read_problem(data + "chute_mu2_step.cdp").contacts, 2.0 * local.impulse_scale);
  EXPECT_GT(peers::factor_mismatch(b, local), 0.1);
}

TEST(PeerLimits, ATraceFitsItsRate)
{
  // error = 10^(-k / 200) after k sweeps, each 1e-4 s: 200 sweeps and 0.02 s per decade.
  std::vector<peers::TracePoint> trace;
  for (int k = 8; k <= 1600; k += 8) trace.push_back({k, 1e-4 * k, std::pow(10.0, -k / 200.0)});
  peers::TailFit fit = peers::fit_tail(trace, 0.0);
  EXPECT_NEAR(fit.rate_per_sweep, std::pow(10.0, -1.0 / 200.0), 1e-9);
  EXPECT_NEAR(fit.decades_per_second, 50.0, 1e-6);
  EXPECT_NEAR(peers::best_error_within(trace, 0.08), 1e-4, 1e-12);
  ASSERT_NE(peers::first_reaching(trace, 1e-6), nullptr);
  EXPECT_EQ(peers::first_reaching(trace, 1e-6)->sweeps, 1200);
  EXPECT_EQ(peers::first_reaching(trace, 1e-9), nullptr);

  // A run that stalls from its middle on (its error rising): the best error no longer falls.
  for (auto& p : trace)
    if (p.sweeps > 800) p.error = 1e-3 * p.sweeps;
  fit = peers::fit_tail(trace, 0.08);
  EXPECT_NEAR(fit.rate_per_sweep, 1.0, 1e-12);
  EXPECT_NEAR(fit.decades_per_second, 0.0, 1e-9);
}

}  // namespace
