// The contacts' per-atom virial (fix_modify virial yes, compute stress/atom): each contact's
// l p / dt split half and half between its grains, across periodic images and ranks. Run on 1
// rank and on 2 (ctest ContactStress.OneRank, ContactStress.TwoRanks), each deck on every rank
// of MPI_COMM_WORLD, the box split along x.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "comm.h"
#include "compute.h"
#include "domain.h"
#include "fmt/format.h"
#include "lammps_session.h"
#include "modify.h"
#include "variable.h"

namespace {

using cdtest::LammpsSession;

constexpr double d = 5e-4;  // m
constexpr double rho = 2500.0;
constexpr double g = 9.81;

// What compute stress/atom and compute pressure are asked for: the per-atom stresses summed over
// the atoms (reduce), the global pressure tensor of the virial alone.
const char* stress_computes = R"(
fix_modify cd virial yes
compute per_atom all stress/atom NULL virial
compute summed all reduce sum c_per_atom[1] c_per_atom[2] c_per_atom[4]
compute global all pressure NULL virial
thermo_style custom step c_summed[1] c_summed[2] c_summed[3] c_global[1] c_global[2] c_global[4]
)";

struct Tensor {
  double xx = 0.0, yy = 0.0, xy = 0.0;
  double largest() const { return std::max({std::abs(xx), std::abs(yy), std::abs(xy)}); }
};

// The pressure tensor from the per-atom stresses, -sum / area (LAMMPS's 2D volume), and from
// compute pressure, at the last step of the run (thermo invoked both there).
struct StressPair {
  Tensor per_atom, global;
  double relative_difference() const
  {
    const double scale = global.largest();
    return std::max({std::abs(per_atom.xx - global.xx), std::abs(per_atom.yy - global.yy),
                     std::abs(per_atom.xy - global.xy)}) /
           scale;
  }
};

// Read at the end of the run, and printed by rank 0 with `what`.
StressPair stresses(LammpsSession& s, const char* what)
{
  auto* variables = s.lmp->input->variable;
  s.commands("variable area equal lx*ly");
  const double area = variables->compute_equal("v_area");
  StressPair pair;
  pair.per_atom = {-variables->compute_equal("c_summed[1]") / area, -variables->compute_equal("c_summed[2]") / area,
                   -variables->compute_equal("c_summed[3]") / area};
  pair.global = {variables->compute_equal("c_global[1]"), variables->compute_equal("c_global[2]"),
                 variables->compute_equal("c_global[4]")};
  if (s.lmp->comm->me == 0)
    fmt::print("{} on {} rank(s): global xx {:.6g} yy {:.6g} xy {:.6g}, per-atom sum relative difference {:.2g}\n",
               what, s.lmp->comm->nprocs, pair.global.xx, pair.global.yy, pair.global.xy, pair.relative_difference());
  return pair;
}

double sum_over_ranks(const LammpsSession& s, double local)
{
  double total = 0.0;
  MPI_Allreduce(&local, &total, 1, MPI_DOUBLE, MPI_SUM, s.lmp->world);
  return total;
}

int world_rank()
{
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank;
}

const std::string pile_restart = "test_contact_stress_pile.restart";

// The physics after read_restart of the pile; `solve` adds to the fix line.
std::string pile_physics(const std::string& solve)
{
  return fmt::format(R"(
comm_modify vel yes
neigh_modify delay 0 every 1 check yes
neighbor {skin} bin
fix grav all gravity {g} vector 0 -1 0
fix cd all contact/dynamics 0.5 0.0 wall yplane 0.0 0.5 0.0 {solve}
fix 2d all enforce2d
)",
                     fmt::arg("skin", 0.2 * d), fmt::arg("g", g), fmt::arg("solve", solve));
}

// 80 disks of diameter d on the sites of a triangular lattice 1.02 d apart, jittered, in a
// 10.2 d wide x-periodic cell above the floor y = 0, settled on one rank for 4000 steps with
// e = 0 and written to a restart file (with the warm start: few sweeps per step on 2 ranks,
// where each sweep is an exchange).
class SettledPile : public ::testing::Test {
 protected:
  static void SetUpTestSuite()
  {
    if (world_rank() == 0) {
      LammpsSession maker(MPI_COMM_SELF);
      maker.commands(cdtest::disk_preamble);
      maker.commands(fmt::format(R"(
boundary p f p
region box block 0 {L} 0 {H} -{r} {r}
create_box 1 box
lattice hex {a} origin 0.5 0.3 0
region fill block 0 {L} 0 {top} -{r} {r} units box
create_atoms 1 region fill
displace_atoms all random {jitter} {jitter} 0 4812 units box
set group all diameter {d} density/disc {rho}
timestep 1e-5
)",
                                 fmt::arg("L", 10 * 1.02 * d), fmt::arg("H", 20 * d), fmt::arg("r", 0.6 * d),
                                 fmt::arg("a", 1.02 * d), fmt::arg("top", 7 * 1.02 * d), fmt::arg("jitter", 0.02 * d),
                                 fmt::arg("d", d), fmt::arg("rho", rho)));
      maker.commands(pile_physics("tolerance 1e-4") + "run 4000\nwrite_restart " + pile_restart);
    }
    MPI_Barrier(MPI_COMM_WORLD);
  }
  static void TearDownTestSuite()
  {
    if (world_rank() == 0) std::remove(pile_restart.c_str());
  }

  // The pile on every rank, split along x, with the stress computes.
  static void load(LammpsSession& s, const std::string& solve)
  {
    s.commands("processors * 1 1\nread_restart " + pile_restart + pile_physics(solve) + stress_computes);
  }
};

// The pile at rest, 20 steps solved to 1e-8: the per-atom sum is the global tensor, and its yy
// the weight's moment about the floor, M g mean y (the floor's contacts count with their branch
// from the contact point at y = 0 to the grain's centre, as a LAMMPS wall fix's virial).
TEST_F(SettledPile, AtRestPerAtomSumIsTheGlobalAndTheWeightsMoment)
{
  LammpsSession s;
  load(s, "tolerance 1e-8 max_iterations 100000");
  s.commands("thermo 20\nrun 20");
  const StressPair pair = stresses(s, "pile at rest");
  EXPECT_LT(pair.relative_difference(), 1e-12) << pair.per_atom.yy << " " << pair.global.yy;
  const auto* atom = s.lmp->atom;
  double mass_local = 0.0, moment_local = 0.0, kinetic_local = 0.0;
  for (int i = 0; i < atom->nlocal; i++) {
    mass_local += atom->rmass[i];
    moment_local += atom->rmass[i] * g * atom->x[i][1];
    kinetic_local += 0.5 * atom->rmass[i] * (atom->v[i][0] * atom->v[i][0] + atom->v[i][1] * atom->v[i][1]);
  }
  const double mass = sum_over_ranks(s, mass_local), moment = sum_over_ranks(s, moment_local);
  const double area = s.lmp->domain->xprd * s.lmp->domain->yprd;
  EXPECT_LT(sum_over_ranks(s, kinetic_local), 1e-6 * mass * g * d) << "the pile must be at rest";
  EXPECT_NEAR(pair.per_atom.yy * area, moment, 1e-4 * moment);
  if (s.lmp->comm->me == 0)
    fmt::print("pile: per-atom sum of yy times area {:.10g}, M g mean y {:.10g}\n", pair.per_atom.yy * area, moment);
}

// The pile tipped into a chute: gravity tilted by 35 degrees (beyond the floor's friction angle),
// 100 steps of flow along the periodic x.
TEST_F(SettledPile, ChutePerAtomSumIsTheGlobal)
{
  LammpsSession s;
  load(s, "tolerance 1e-4");
  const double angle = 35.0 * M_PI / 180.0;
  s.commands(
      fmt::format("fix grav all gravity {} vector {} {} 0\nthermo 100\nrun 100", g, std::sin(angle), -std::cos(angle)));
  const StressPair pair = stresses(s, "chute");
  EXPECT_GT(std::abs(pair.global.xy), 1e-3 * pair.global.yy) << "a shear stress";
  EXPECT_LT(pair.relative_difference(), 1e-12) << pair.per_atom.xy << " " << pair.global.xy;
}

// A Lees-Edwards cell (inputs/examples/in.plane_shear, 8 x 8 disks): pressed to phi = 0.75, then
// sheared to a strain of 0.4; pairs meet across the sheared side.
TEST(ContactStress, ShearedCellPerAtomSumIsTheGlobal)
{
  LammpsSession s;
  s.commands(R"(
units lj
dimension 2
atom_style sphere
atom_modify map hash
comm_modify vel yes
processors * 1 1
boundary p p p
lattice sq 0.591715976
region box prism 0 8 0 8 -0.5 0.5 0 0 0
create_box 1 box
create_atoms 1 box
variable diameter atom 0.8+0.4*random(0,1,48213)
set group all diameter v_diameter
set group all density/disc 1.0
displace_atoms all random 0.04 0.04 0 48213 units box
neighbor 0.3 bin
neigh_modify delay 0 every 1 check yes
timestep 0.02
fix cd all contact/dynamics 0.0 0.0 tolerance 1e-3
fix 2d all enforce2d
compute grain all property/atom radius
variable disk_area atom PI*c_grain[1]^2
compute grains_area all reduce sum v_disk_area
thermo_style custom step c_grains_area
run 0
variable side equal $(sqrt(c_grains_area/0.75):%.12g)
fix press all deform 1 x final 0 ${side} y final 0 ${side} remap v units box
run 1000
unfix press
unfix cd
velocity all set 0 0 0
velocity all ramp vx 0 $(0.1*ly:%.12g) y $(ylo:%.12g) $(yhi:%.12g) sum no units box
fix cd all contact/dynamics 0.5 0.0 tolerance 1e-4 max_iterations 10000
fix shear all deform 1 xy erate 0.1 remap v flip yes
)");
  s.commands(stress_computes);
  s.commands("thermo 100\nrun 200");
  const StressPair pair = stresses(s, "sheared cell");
  EXPECT_GT(pair.global.yy, 0.0) << "a loaded cell";
  EXPECT_GT(std::abs(pair.global.xy), 0.05 * pair.global.yy) << "a shear stress";
  EXPECT_LT(pair.relative_difference(), 1e-12) << pair.per_atom.yy << " " << pair.global.yy;
}

// Two disks meeting head on through the periodic side x = 0 = L (on 2 ranks, owned by different
// ranks): the impulse p = m v (1 + e) / 2 at a branch of d less the predictor's closing v dt / 2
// goes half to each disk, -stress xx = l p / (2 dt) each.
TEST(ContactStress, ImpactAcrossThePeriodicSideIsSplitHalfAndHalf)
{
  LammpsSession s;
  s.commands(cdtest::disk_preamble);
  const double L = 10 * d, v = 0.2, e = 0.5, dt = 1e-5;
  s.commands(fmt::format(R"(
processors * 1 1
boundary p p p
region box block 0 {L} 0 {L} -{r} {r}
create_box 1 box
create_atoms 1 single {xa} {y} 0
create_atoms 1 single {xb} {y} 0
set group all diameter {d} density/disc {rho}
set atom 1 vx {v}
neighbor {skin} bin
timestep {dt}
fix cd all contact/dynamics 0.3 {e} tolerance 1e-12
fix 2d all enforce2d
)",
                         fmt::arg("L", L), fmt::arg("r", 0.5 * d), fmt::arg("xa", L - 0.5 * d), fmt::arg("xb", 0.5 * d),
                         fmt::arg("y", 0.5 * L), fmt::arg("d", d), fmt::arg("rho", rho), fmt::arg("v", v),
                         fmt::arg("skin", 0.2 * d), fmt::arg("dt", dt), fmt::arg("e", e)));
  s.commands(stress_computes);
  s.commands("run 1");
  const double mass = M_PI * 0.25 * d * d * rho;
  const double half = 0.5 * (d - 0.5 * v * dt) * (mass * v * (1 + e) / 2) / dt;
  auto* compute = s.lmp->modify->compute[s.lmp->modify->find_compute("per_atom")];
  const auto* atom = s.lmp->atom;
  int disks_here = 0;
  for (int i = 0; i < atom->nlocal; i++, disks_here++) {
    EXPECT_NEAR(-compute->array_atom[i][0], half, 1e-9 * half) << "atom " << atom->tag[i];
    EXPECT_NEAR(compute->array_atom[i][1], 0.0, 1e-9 * half);
  }
  if (s.lmp->comm->nprocs == 2) EXPECT_EQ(disks_here, 1) << "each rank owns one disk";
}

}  // namespace
