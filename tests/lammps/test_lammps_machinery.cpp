// The fix works with LAMMPS's insertion, output and averaging machinery.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "lammps_session.h"
#include "small_deposition.h"

namespace {

using cdtest::LammpsSession;
constexpr double d = cdtest::deposition_d;

TEST(Machinery, PouredGrainsGetDiscMassesAndSettle)
{
  LammpsSession s;
  // fix pour needs a hash atom map in this LAMMPS (FixContactDynamics::check_insertion_map).
  std::string preamble = cdtest::disk_preamble;
  preamble.replace(preamble.find("map array"), 9, "map hash");
  s.commands(preamble);
  s.commands(fmt::format(R"(
boundary p f p
region box block 0 {L} 0 {H} -{r} {r}
create_box 1 box
region pour block 0 {L} {lo} {hi} -{r} {r} units box
neighbor {skin} bin
timestep 1e-5
fix grav all gravity 9.81 vector 0 -1 0
fix pour all pour 60 1 4242 region pour diam range {dmin} {dmax} dens 2500 2500
fix cd all contact/dynamics 0.5 0.5 density 2500 wall yplane 0.0 0.5 0.5
fix 2d all enforce2d
run 3000
)",
                         fmt::arg("L", 20 * d), fmt::arg("H", 40 * d), fmt::arg("r", 0.6 * d), fmt::arg("lo", 20 * d),
                         fmt::arg("hi", 38 * d), fmt::arg("skin", 0.2 * d), fmt::arg("dmin", 0.8 * d),
                         fmt::arg("dmax", 1.2 * d)));
  const auto* atom = s.lmp->atom;
  ASSERT_GT(atom->natoms, 40);  // fix pour may place fewer than asked in a crowded region
  for (int i = 0; i < atom->nlocal; i++)
    EXPECT_NEAR(atom->rmass[i], M_PI * atom->radius[i] * atom->radius[i] * 2500.0, 1e-12 * atom->rmass[i]);
}

TEST(Machinery, LocalContactArrayFeedsDumpLocalAndVectorFeedsAveTime)
{
  LammpsSession s;
  s.commands(cdtest::disk_preamble);
  s.commands(cdtest::small_deposition(12, "tolerance 1e-6"));
  s.commands(R"(
run 5000
dump contacts all local 100 test_machinery.contacts f_cd[1] f_cd[2] f_cd[3] f_cd[4] f_cd[5] f_cd[6] f_cd[7]
dump_modify contacts format float %.17g
fix solver all ave/time 10 10 100 f_cd[1] f_cd[4] f_cd[5] file test_machinery.solver
run 100
undump contacts
unfix solver
)");  // undump and unfix close (flush) the files
  LAMMPS_NS::Fix* fix = s.fix("cd");
  const int loaded = static_cast<int>(fix->compute_vector(3));
  EXPECT_GT(loaded, 100);  // 144 grains piling up on the floor
  EXPECT_EQ(fix->size_local_rows, loaded);

  // The last dump block lists one row per loaded contact: atom IDs, wall index, impulses.
  std::ifstream dump("test_machinery.contacts");
  std::string line;
  int entries = -1, rows = 0;
  bool in_entries = false;
  double floor_impulse = 0.0;  // in the last block
  while (std::getline(dump, line)) {
    if (line.rfind("ITEM:", 0) == 0) {
      in_entries = line.rfind("ITEM: ENTRIES", 0) == 0;
      if (line.rfind("ITEM: NUMBER OF ENTRIES", 0) == 0) {
        std::getline(dump, line);
        entries = std::stoi(line);
        rows = 0;
        floor_impulse = 0.0;
      }
    } else if (in_entries) {
      double a, b, wall, p_n, p_t;
      std::sscanf(line.c_str(), "%lf %lf %lf %lf %lf", &a, &b, &wall, &p_n, &p_t);
      EXPECT_GT(p_n, 0.0);
      EXPECT_LE(std::abs(p_t), 0.5 * p_n * (1 + 1e-12));
      if (wall == 1.0) floor_impulse += p_n;
      ++rows;
    }
  }
  EXPECT_EQ(rows, entries);
  EXPECT_EQ(entries, loaded);
  EXPECT_GT(floor_impulse, 0.0);

  std::ifstream solver("test_machinery.solver");
  int samples = 0;
  while (std::getline(solver, line))
    if (!line.empty() && line[0] != '#') ++samples;
  EXPECT_EQ(samples, 1);  // step 5100: 10 samples every 10 steps
  std::remove("test_machinery.contacts");
  std::remove("test_machinery.solver");
}

}  // namespace
