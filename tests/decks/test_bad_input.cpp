// Every bad input stops lmp_cd with a one-line error naming the problem. Each case runs the
// executable on a deck and checks the exit status and the ERROR line.
#include <gtest/gtest.h>

#include <string>

#include "lmp_cd_run.h"

namespace {

using cdtest::error_line;
using cdtest::run_deck;
using cdtest::RunResult;

const std::string& preamble = cdtest::two_grains;

struct BadCase {
  const char* name;
  std::string deck;
  const char* message;  // must appear in the ERROR line
};

class BadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadInput, StopsWithAOneLineErrorNamingTheProblem)
{
  const BadCase& c = GetParam();
  const RunResult result = run_deck(c.name, c.deck);
  EXPECT_NE(result.exit_status, 0) << result.output;
  const std::string line = error_line(result.output);
  EXPECT_NE(line.find(c.message), std::string::npos) << "ERROR line: " << line << "\n" << result.output;
}

std::string with_fix(const std::string& fix_arguments)
{
  return preamble + "fix cd all contact/dynamics " + fix_arguments + "\nrun 10\n";
}

// The two grains with a region (its lines given) as a wall (`wall region` followed by `wall`).
std::string with_region(const std::string& region_lines, const std::string& wall)
{
  return preamble + region_lines + "\nfix cd all contact/dynamics 0.5 0.5 wall region " + wall + "\nrun 10\n";
}

// Two grains in a periodic box tilted along x, sheared by fix deform on `group`.
std::string sheared_box(const std::string& remap, const std::string& group, const std::string& fix_extra)
{
  return "units si\ndimension 2\natom_style sphere\natom_modify map array\ncomm_modify vel yes\n"
         "neigh_modify delay 0 every 1 check yes\nboundary p p p\n"
         "region box prism 0 0.01 0 0.01 -0.001 0.001 0 0 0\ncreate_box 1 box\n"
         "create_atoms 1 single 0.002 0.005 0\ncreate_atoms 1 single 0.006 0.005 0\n"
         "set group all diameter 0.001 density/disc 2500\ngroup one id 1\nneighbor 2e-4 bin\ntimestep 1e-5\n"
         "fix shear " +
         group + " deform 1 xy erate 1 " + remap + "\nfix cd all contact/dynamics 0.5 0.5" + fix_extra + "\nrun 1\n";
}

const BadCase bad_cases[] = {
    {"negative_mu", with_fix("-0.1 0.5"), "mu must be >= 0, got -0.1"},
    {"restitution_above_one", with_fix("0.5 1.5"), "e must be in [0,1], got 1.5"},
    {"mu_not_a_number", with_fix("abc 0.5"), "mu expects a number, got 'abc'"},
    {"missing_e", with_fix("0.5"), "needs mu and e"},
    {"unknown_keyword", with_fix("0.5 0.5 tolerence 1e-4"), "unknown keyword 'tolerence'"},
    {"zero_tolerance", with_fix("0.5 0.5 tolerance 0"), "tolerance must be in (0,1), got 0"},
    {"tolerance_of_one", with_fix("0.5 0.5 tolerance 1"), "tolerance must be in (0,1), got 1"},
    {"tolerance_huge", with_fix("0.5 0.5 tolerance 1e300"), "tolerance must be in (0,1), got 1e+300"},
    {"keyword_given_twice", with_fix("0.5 0.5 tolerance 1e-3 theta 0.6 tolerance 1e-4"),
     "tolerance given twice; give each keyword once"},
    {"zero_iteration_cap", with_fix("0.5 0.5 max_iterations 0"), "max_iterations must be >= 1, got 0"},
    {"fractional_iteration_cap", with_fix("0.5 0.5 max_iterations 2.5"),
     "max_iterations expects an integer, got '2.5'"},
    {"theta_out_of_range", with_fix("0.5 0.5 theta 0.3"), "theta must be in [0.5,1], got 0.3"},
    {"relaxation_out_of_range", with_fix("0.5 0.5 relaxation 1.5"), "relaxation must be in (0,1], got 1.5"},
    {"over_relaxation_of_two", with_fix("0.5 0.5 over_relaxation 2"), "over_relaxation must be in [1,2), got 2"},
    {"negative_stall_window", with_fix("0.5 0.5 stall_window -1"), "stall_window must be >= 0, got -1"},
    {"stall_coherence_of_one", with_fix("0.5 0.5 stall_coherence 1"), "stall_coherence must be in (0,1), got 1"},
    {"stall_relaxation_zero", with_fix("0.5 0.5 stall_relaxation 0"), "stall_relaxation must be in (0,1], got 0"},
    {"negative_stall_block", with_fix("0.5 0.5 stall_block -1"), "stall_block must be >= 0, got -1"},
    {"negative_stall_block_every", with_fix("0.5 0.5 stall_block_every -2"), "stall_block_every must be >= 0, got -2"},
    {"save_problems_without_prefix", with_fix("0.5 0.5 save_problems 100"),
     "save_problems needs 2 values: sweeps prefix"},
    {"save_problems_negative", with_fix("0.5 0.5 save_problems -5 hard"), "save_problems sweeps must be >= 0, got -5"},
    {"unknown_norm", with_fix("0.5 0.5 norm l2"), "norm must be quadratic or maximum, got 'l2'"},
    {"unknown_solver", with_fix("0.5 0.5 solver nsgs"), "solver must be gauss_seidel, got 'nsgs'"},
    {"unknown_order", with_fix("0.5 0.5 order random"), "order must be fixed or shuffle, got 'random'"},
    {"unknown_join", with_fix("0.5 0.5 join before"), "join must be during or after, got 'before'"},
    {"unknown_newton_polish", with_fix("0.5 0.5 newton_polish on"), "newton_polish must be no or yes, got 'on'"},
    {"unknown_acceleration", with_fix("0.5 0.5 acceleration anderson"),
     "acceleration must be none or conjugate, got 'anderson'"},
    {"zero_full_sweep_every", with_fix("0.5 0.5 full_sweep_every 0"), "full_sweep_every must be >= 1, got 0"},
    {"fractional_full_sweep_every", with_fix("0.5 0.5 full_sweep_every 1.5"),
     "full_sweep_every expects an integer, got '1.5'"},
    {"missing_value", with_fix("0.5 0.5 tolerance"), "tolerance needs 1 value"},
    {"zero_dt_max", with_fix("0.5 0.5 dt_max 0"), "dt_max must be > 0, got 0"},
    {"align_without_dt_max", with_fix("0.5 0.5 dt_align 1e-3"), "dt_align needs dt_max (the adaptive step)"},
    {"travel_without_dt_max", with_fix("0.5 0.5 travel 0.3"), "travel needs dt_max (the adaptive step)"},
    {"align_not_a_multiple", with_fix("0.5 0.5 dt_max 1e-4 dt_align 1.5e-4"),
     "dt_align 0.00015 must be a whole multiple of dt_max 0.0001"},
    // 5 steps of 1e-5 s: the grid of 1e-3 s periods would start between two of them.
    {"step_grid_between_periods",
     preamble + "run 5\nfix cd all contact/dynamics 0.5 0.5 dt_max 1e-4 dt_align 1e-3\nrun 10\n",
     "the step grid cannot start at time 5e-05 s, not a whole number of alignment periods (0.001 s)"},
    {"travel_beyond_half_skin", with_fix("0.5 0.5 dt_max 1e-4 travel 0.6"),
     "travel must be in (0,0.5] (a fraction of the neighbour skin), got 0.6"},
    // The preamble's skin is 1e-4 m: at 2000 m/s even dt_max/2^12 moves a grain 4.9e-5 m > 0.4 skin.
    {"grain_faster_than_any_step",
     preamble + "set atom 1 vx 2000\nfix cd all contact/dynamics 0.5 0.5 dt_max 1e-4\nrun 10\n",
     "atom 1 moves at 2000 m/s; the smallest step"},
    {"negative_type_mu", with_fix("0.5 0.5 mu/types 1 2 -1"), "mu/types must be >= 0, got -1"},
    // The preamble has 2 atom types.
    {"type_beyond_the_types", with_fix("0.5 0.5 mu/types 1 3 0.2"),
     "mu/types type '3' is not a type or range of types within 1-2"},
    {"type_range_from_zero", with_fix("0.5 0.5 e/types 0*1 1 0.2"),
     "e/types type '0*1' is not a type or range of types within 1-2"},
    {"type_range_reversed", with_fix("0.5 0.5 mu/types 1 2*1 0.2"),
     "mu/types type '2*1' is not a type or range of types within 1-2"},
    {"type_not_a_number", with_fix("0.5 0.5 e/types a 1 0.2"), "e/types expects an integer, got 'a'"},
    {"type_law_missing_value", with_fix("0.5 0.5 mu/types 1 1"), "mu/types needs 3 values: I J mu"},
    {"number_without_digits", with_fix("0.5 0.5 tolerance e"), "tolerance expects a number, got 'e'"},
    {"number_with_two_points", with_fix("0.5 0.5 relaxation 0.5.1"), "relaxation expects a number, got '0.5.1'"},
    {"number_overflowing", with_fix("0.5 0.5 alert 1e999"), "alert '1e999' is outside the range of a double"},
    {"number_underflowing", with_fix("0.5 0.5 tolerance 1e-400"),
     "tolerance '1e-400' is outside the range of a double"},
    {"mu_overflowing", with_fix("1e999 0.5"), "mu '1e999' is outside the range of a double"},
    {"integer_overflowing", with_fix("0.5 0.5 max_iterations 99999999999"),
     "max_iterations must fit an int, got '99999999999'"},
    {"integer_with_inner_sign", with_fix("0.5 0.5 full_sweep_every 1-2"),
     "full_sweep_every expects an integer, got '1-2'"},
    {"integer_sign_alone", with_fix("0.5 0.5 max_contacts -"), "max_contacts expects an integer, got '-'"},
    {"seed_overflowing", with_fix("0.5 0.5 order shuffle 99999999999"),
     "order shuffle seed must fit an int, got '99999999999'"},
    {"seed_zero", with_fix("0.5 0.5 order shuffle 0"), "order shuffle seed must be > 0, got 0"},
    {"max_contacts_beyond_limit", with_fix("0.5 0.5 max_contacts 1000000000"),
     "max_contacts must be in [1,1000], got 1000000000"},
    {"warm_start_not_yes_or_no", with_fix("0.5 0.5 warm_start 1"), "warm_start must be yes or no, got '1'"},
    {"negative_alert", with_fix("0.5 0.5 alert -1"), "alert must be >= 0, got -1"},
    // The preamble's skin is 1e-4 m.
    {"alert_beyond_the_skin", with_fix("0.5 0.5 alert 2e-4"),
     "alert 0.0002 is larger than the neighbour skin 0.0001: pairs that far apart are not listed"},
    {"zero_density", with_fix("0.5 0.5 density 0"), "density must be > 0, got 0"},
    {"zero_dt_align", with_fix("0.5 0.5 dt_max 1e-4 dt_align 0"), "dt_align must be > 0, got 0"},
    {"wall_missing_restitution", with_fix("0.5 0.5 wall yplane 0 0.5"), "wall yplane needs 3 values: position mu e"},
    {"wall_without_shape", with_fix("0.5 0.5 wall"),
     "wall needs a shape and its values: xplane position mu e, yplane position mu e, segment x1 y1 x2 y2 mu e or "
     "region ID mu e"},
    {"segment_missing_values", with_fix("0.5 0.5 wall segment 0 0 0.005"),
     "wall segment needs 6 values: x1 y1 x2 y2 mu e"},
    {"wall_position_not_a_number", with_fix("0.5 0.5 wall xplane x 0.5 0.5"), "wall xplane expects a number, got 'x'"},
    {"wall_negative_mu", with_fix("0.5 0.5 wall segment 0 0 0 0.005 -1 0.5"), "wall mu must be >= 0, got -1"},
    {"zero_length_segment", with_fix("0.5 0.5 wall segment 0 0 0 0 0.5 0.5"), "wall segment has zero length"},
    {"wall_outside_box", with_fix("0.5 0.5 wall yplane -0.001 0.5 0.5"), "wall yplane at -0.001 is outside the box"},
    {"segment_outside_box", with_fix("0.5 0.5 wall segment 0 0 0 0.02 0.5 0.5"),
     "wall segment end (0, 0.02) is outside the box"},
    {"unknown_wall", with_fix("0.5 0.5 wall zplane 0 0.5 0.5"),
     "wall must be xplane, yplane, segment or region, got 'zplane'"},
    {"wall_restitution", with_fix("0.5 0.5 wall yplane 0 0.5 2"), "wall e must be in [0,1], got 2"},
    {"wall_region_missing_values", with_fix("0.5 0.5 wall region cup 0.5"), "wall region needs 3 values: ID mu e"},
    {"wall_region_unknown", with_fix("0.5 0.5 wall region nowhere 0.5 0.5"), "wall region nowhere does not exist"},
    {"wall_region_restitution", with_region("region cup sphere 0.005 0.005 0 0.004", "cup 0.5 1.5"),
     "wall e must be in [0,1], got 1.5"},
    {"wall_region_changing_shape",
     with_region("variable size equal 0.004+time\nregion cup sphere 0.005 0.005 0 v_size", "cup 0.5 0.5"),
     "region cup (sphere) changes its shape with variables; walls must be rigid"},
    {"wall_region_turning_out_of_plane",
     with_region("variable turn equal time\nregion drum cylinder z 0.005 0.005 0.004 INF INF rotate v_turn 0 0 0 1 0 0",
                 "drum 0.5 0.5"),
     "region drum (cylinder) rotates about an axis that is not along z"},
    {"wall_region_union_of_moving_part",
     with_region("variable shift equal time\nregion a sphere 0.005 0.005 0 0.004 move v_shift NULL NULL\n"
                 "region b block 0.001 0.009 0 0.002 INF INF\nregion both union 2 a b",
                 "both 0.5 0.5"),
     "region both (union) combines moving region a; give the moving region a wall region keyword of its own"},
    {"wall_region_moving_along_z",
     with_region("variable rise equal time\nregion cup sphere 0.005 0.005 0 0.004 move NULL NULL v_rise",
                 "cup 0.5 0.5"),
     "wall region cup moves along z"},
    {"wall_region_off_the_plane", with_region("region cup sphere 0.005 0.003 0.0002 0.003", "cup 0.5 0.5"),
     "wall region cup meets the plane z = 0 obliquely"},
    {"dimension_3",
     "units si\natom_style sphere\nregion box block 0 1 0 1 0 1\ncreate_box 1 box\n"
     "fix cd all contact/dynamics 0.5 0.5\n",
     "requires dimension 2"},
    // A tilted box is followed (tests/lammps/test_sheared_cell.cpp); a deforming one only with remap v.
    {"deform_remap_x", sheared_box("remap x", "all", ""),
     "fix shear (deform) must use remap v: remap x moves grains through their contacts"},
    {"deform_remap_none", sheared_box("remap none", "all", ""), "fix shear (deform) must use remap v"},
    {"deform_of_a_group", sheared_box("remap v", "one", ""),
     "fix shear (deform) must act on group all to remap every velocity"},
    {"deform_with_adaptive_step", sheared_box("remap v", "all", " dt_max 1e-5"),
     "fix shear (deform) counts steps, not time: it cannot follow dt_max"},
    {"barostat",
     "units si\ndimension 2\natom_style sphere\natom_modify map array\ncomm_modify vel yes\nboundary p p p\n"
     "region box block 0 0.01 0 0.01 -0.001 0.001\ncreate_box 1 box\ncreate_atoms 1 single 0.002 0.005 0\n"
     "set group all diameter 0.001 density/disc 2500\nfix baro all press/berendsen x 0 0 1 y 0 0 1\n"
     "fix cd all contact/dynamics 0.5 0.5\nrun 1\n",
     "fix baro (press/berendsen) changes the box and moves the grains with it: only fix deform with remap v is "
     "followed"},
    {"atom_style_without_radius",
     "units si\ndimension 2\natom_style atomic\nregion box block 0 1 0 1 -0.1 0.1\ncreate_box 1 box\n"
     "fix cd all contact/dynamics 0.5 0.5\n",
     "requires atom_style sphere"},
    {"ghost_velocities_off",
     [] {
       std::string deck = with_fix("0.5 0.5");
       deck.replace(deck.find("comm_modify vel yes"), 19, "comm_modify vel no");
       return deck;
     }(),
     "use comm_modify vel yes"},
    {"no_atom_map",
     [] {
       std::string deck = with_fix("0.5 0.5");
       deck.replace(deck.find("atom_modify map array"), 21, "");
       return deck;
     }(),
     "requires an atom map: use atom_modify map hash"},
    {"neighbour_delay",
     [] {
       std::string deck = with_fix("0.5 0.5");
       deck.replace(deck.find("neigh_modify delay 0"), 20, "neigh_modify delay 5");
       return deck;
     }(),
     "use neigh_modify delay 0 every 1 check yes"},
    {"step_longer_than_half_skin", preamble + "set atom 1 vx 20.0\nfix cd all contact/dynamics 0.5 0.5\nrun 1\n",
     "atom 1 moved 0.0002 in step 1, more than half the neighbour skin 0.0001"},
    {"pour_with_step_grid",
     [] {
       std::string deck = preamble;
       deck.replace(deck.find("map array"), 9, "map hash");
       return deck +
              "fix g all gravity 9.81 vector 0 -1 0\n"
              "region slab block 0.001 0.009 0.006 0.009 -0.0003 0.0003 units box\n"
              "fix pour all pour 4 1 4767548 diam one 5e-4 dens 2500 2500 region slab\n"
              "fix cd all contact/dynamics 0.5 0.5 density 2500 dt_max 1e-5\nrun 1\n";
     }(),
     "fix pour (pour) cannot follow dt_max: it stops the run when the step changes; pour at a fixed step"},
    {"move_with_step_grid",
     preamble + "group floor id 1\ngroup grains id 2\nfix conveyor floor move linear 0.01 0 0 units box\n"
                "fix cd grains contact/dynamics 0.5 0.5 dt_max 1e-5\nrun 1\n",
     "fix conveyor (move) cannot follow dt_max: it stops the run when the step changes; give the step with "
     "timestep instead of dt_max"},
    {"second_integrator", preamble + "fix nve all nve/sphere\nfix cd all contact/dynamics 0.5 0.5\nrun 1\n",
     "fix nve (nve/sphere) also integrates atoms of group all"},
    {"pair_style_on_the_group",
     preamble +
         "pair_style gran/hooke 2000 NULL 0 NULL 0.5 0\npair_coeff * *\nfix cd all contact/dynamics 0.5 0.5\nrun 1\n",
     "pair style gran/hooke also acts on atoms of group all (types 1 and 1); remove it, or add pair_forces yes"},
    {"pair_forces_not_yes_or_no", with_fix("0.5 0.5 pair_forces maybe"), "pair_forces must be yes or no, got 'maybe'"},
    {"sphere_masses",
     preamble + "set atom 2 diameter 4e-4\nset group all density 2500\nfix cd all contact/dynamics 0.5 0.5\nrun 1\n",
     "has sphere masses"},
    {"non_finite_velocity",
     // An infinite external force (a user variable overflowing) reaches the solver.
     preamble + "variable huge equal 1e308*10\nfix push all addforce v_huge 0.0 0.0\n"
                "fix cd all contact/dynamics 0.5 0.5\nrun 1\n",
     "non-finite velocity of atom 1 at step 1"},
    {"too_many_contacts",
     // The bottom disk of a resting pair carries the floor and the upper disk: two contacts.
     preamble + "set atom 2 x 0.005 y 0.00075\nfix g all gravity 9.81 vector 0 -1 0\n"
                "fix cd all contact/dynamics 0.5 0.5 max_contacts 1 wall yplane 0 0.5 0.5\nrun 1\n",
     "atom 1 has more than 1 loaded contacts; raise max_contacts"},
    {"cell_shorter_than_a_grain",
     // An x-periodic cell 0.8 d long: the grain overlaps its own periodic image.
     [] {
       std::string deck = preamble;
       deck.replace(deck.find("block 0 0.01 0 0.01"), 19, "block 0 0.0004 0 0.01");
       deck.replace(deck.find("create_atoms 1 single 0.005 0.00025 0\ncreate_atoms 1 single 0.006 0.00025 0"), 75,
                    "create_atoms 1 single 0.0002 0.00025 0");
       return deck + "fix cd all contact/dynamics 0.5 0.5\nrun 1\n";
     }(),
     "atom 1 touches its own periodic image; the cell is too short"},
};

INSTANTIATE_TEST_SUITE_P(Decks, BadInput, ::testing::ValuesIn(bad_cases),
                         [](const auto& info) { return std::string(info.param.name); });

// A grain that moved more than half the skin stops every rank with the one line, as LAMMPS's own
// errors do, not with an MPI abort and its banner.
TEST(Stops, TheSkinStopEndsTheRunWithoutAnMpiAbort)
{
  const RunResult result =
      run_deck("skin_stop", preamble + "set atom 1 vx 20.0\nfix cd all contact/dynamics 0.5 0.5\nrun 1\n");
  EXPECT_NE(result.exit_status, 0) << result.output;
  EXPECT_NE(error_line(result.output).find("more than half the neighbour skin"), std::string::npos) << result.output;
  EXPECT_EQ(result.output.find("MPI_ABORT"), std::string::npos) << result.output;
}

TEST(Warnings, OverlapsAtTheStartOfARunAreReported)
{
  // Two grains 0.4 d apart, centre to centre: rigid contacts would keep that overlap.
  const RunResult overlapping = run_deck("initial_overlap", preamble +
                                                                "set atom 2 x 0.0052\n"
                                                                "fix cd all contact/dynamics 0.5 0.5\nrun 0\n");
  EXPECT_EQ(overlapping.exit_status, 0) << overlapping.output;
  EXPECT_NE(overlapping.output.find("1 contacts overlap by up to 0.6 mean diameters at the start"), std::string::npos)
      << overlapping.output;
  const RunResult apart = run_deck("no_initial_overlap", with_fix("0.5 0.5"));
  EXPECT_EQ(apart.output.find("overlap by up to"), std::string::npos) << apart.output;
}

// Masses of one radius cannot tell disks from spheres (m/r^2 and m/r^3 are both uniform): the
// fix prints, once, the areal density they imply; sphere masses of rho 2500 read as 4/3 r rho.
TEST(Masses, OneRadiusMassesAreReportedWithTheArealDensityTheyImply)
{
  const char* note = "have one radius: their masses are disks of areal density ";
  const RunResult spheres =
      run_deck("one_radius_spheres", preamble +
                                         "set group all density 2500\nfix cd all contact/dynamics 0.5 0.5\n"
                                         "run 1\nrun 1\n");
  EXPECT_EQ(spheres.exit_status, 0) << spheres.output;
  const std::size_t at = spheres.output.find(note);
  ASSERT_NE(at, std::string::npos) << spheres.output;
  EXPECT_EQ(spheres.output.substr(at + std::string(note).size(), 8), "0.833333") << spheres.output;
  EXPECT_EQ(spheres.output.find(note, at + 1), std::string::npos) << "once per fix\n" << spheres.output;
  const RunResult discs = run_deck("one_radius_discs", with_fix("0.5 0.5"));
  EXPECT_NE(discs.output.find(std::string(note) + "2500 "), std::string::npos) << discs.output;
  const RunResult reset = run_deck("one_radius_density_keyword", with_fix("0.5 0.5 density 2500"));
  EXPECT_EQ(reset.output.find(note), std::string::npos) << reset.output;
}

TEST(PairForces, KeptWhenAskedFor)
{
  // Two grains 0.4 d apart, centre to centre: the rigid contacts keep the overlap, a Hooke
  // spring pushes them apart; with pair_forces yes both act and the pair separates.
  const std::string deck = preamble +
                           "set atom 2 x 0.0052\npair_style gran/hooke 2000 NULL 0 NULL 0.5 0\n"
                           "pair_coeff * *\nfix cd all contact/dynamics 0.5 0.5 pair_forces yes\nrun 20\n"
                           "print \"SEPARATION $(x[2]-x[1])\"\n";
  const RunResult result = run_deck("pair_forces_yes", deck);
  EXPECT_EQ(result.exit_status, 0) << result.output;
  EXPECT_EQ(error_line(result.output), "") << result.output;
  const std::size_t at = result.output.find("\nSEPARATION ");
  ASSERT_NE(at, std::string::npos) << result.output;
  EXPECT_GT(std::stod(result.output.substr(at + 12)), 2.1e-4) << result.output;
}

TEST(PairForces, PairStyleZeroAndTypesOutsideTheGroupAreAccepted)
{
  // pair_style zero exerts no force; a pair style acting only on type 2 (not in the group,
  // hybrid none for the group's type pairs) leaves the group's contacts alone.
  const RunResult zero = run_deck("pair_zero", preamble +
                                                   "pair_style zero 1e-3\npair_coeff * *\n"
                                                   "fix cd all contact/dynamics 0.5 0.5\nrun 5\n");
  EXPECT_EQ(zero.exit_status, 0) << zero.output;
  EXPECT_EQ(error_line(zero.output), "") << zero.output;
  const RunResult other_types =
      run_deck("pair_other_types", preamble +
                                       "set atom 2 type 2\ngroup grains type 1\n"
                                       "pair_style hybrid gran/hooke 2000 NULL 0 NULL 0.5 0\npair_coeff 1 * none\n"
                                       "pair_coeff 2 2 gran/hooke\nfix cd grains contact/dynamics 0.5 0.5\nrun 5\n");
  EXPECT_EQ(other_types.exit_status, 0) << other_types.output;
  EXPECT_EQ(error_line(other_types.output), "") << other_types.output;
}

TEST(MultipleRanks, SubdomainsThinnerThanTheContactCutoffAreRefused)
{
  // Two ranks along x on a box 2 d wide: each subdomain (1 d) is thinner than 2 d_max + skin.
  const std::string deck =
      "units si\ndimension 2\natom_style sphere\natom_modify map array\n"
      "comm_modify vel yes\nneigh_modify delay 0\nprocessors 2 1 1\nboundary p f p\n"
      "region box block 0 0.001 0 0.01 -0.0003 0.0003\ncreate_box 1 box\n"
      "create_atoms 1 single 0.0005 0.00025 0\n"
      "set group all diameter 5e-4 density/disc 2500\nneighbor 1e-4 bin\n"
      "timestep 1e-5\nfix cd all contact/dynamics 0.5 0.5 wall yplane 0 0.5 0.5\n"
      "run 1\n";
  const RunResult result = run_deck("thin_subdomains", deck, "mpirun --allow-run-as-root --oversubscribe -np 2 ");
  EXPECT_NE(result.exit_status, 0);
  EXPECT_NE(error_line(result.output).find("an MPI subdomain is thinner than the contact cutoff"), std::string::npos)
      << result.output;
}

// Two ranks along x on a box of the given width, two grains, two runs.
std::string two_rank_deck(const std::string& box_width)
{
  return "units si\ndimension 2\natom_style sphere\natom_modify map array\ncomm_modify vel yes\n"
         "neigh_modify delay 0\nprocessors 2 1 1\nboundary p f p\n"
         "region box block 0 " +
         box_width +
         " 0 0.01 -0.0003 0.0003\ncreate_box 1 box\n"
         "create_atoms 1 single 0.0004 0.00025 0\ncreate_atoms 1 single 0.0012 0.00025 0\n"
         "set group all diameter 5e-4 density/disc 2500\nneighbor 1e-4 bin\ntimestep 1e-5\n"
         "fix cd all contact/dynamics 0.5 0.5 wall yplane 0 0.5 0.5\nrun 5\nrun 5\n";
}

// Two grains too fast for the skin on two ranks: every rank stops with the one line, which names
// the farther (atom 2, on rank 1: 2e-4 m in the step, atom 1 on rank 0: 1e-4 m).
TEST(MultipleRanks, TheSkinStopNamesTheFarthestGrainWithoutAnMpiAbort)
{
  const std::string deck =
      "units si\ndimension 2\natom_style sphere\natom_modify map array\ncomm_modify vel yes\n"
      "neigh_modify delay 0\nprocessors 2 1 1\nboundary p f p\n"
      "region box block 0 0.003 0 0.01 -0.0003 0.0003\ncreate_box 1 box\n"
      "create_atoms 1 single 0.0004 0.00025 0\ncreate_atoms 1 single 0.0022 0.00025 0\n"
      "set group all diameter 5e-4 density/disc 2500\nneighbor 1e-4 bin\ntimestep 1e-5\n"
      "set atom 1 vx 10.0\nset atom 2 vx 20.0\nfix cd all contact/dynamics 0.5 0.5\nrun 1\n";
  const RunResult result = run_deck("skin_stop_two_ranks", deck, "mpirun --allow-run-as-root --oversubscribe -np 2 ");
  EXPECT_NE(result.exit_status, 0) << result.output;
  EXPECT_NE(error_line(result.output).find("atom 2 moved 0.0002 in step 1, more than half the neighbour skin"),
            std::string::npos)
      << result.output;
  EXPECT_EQ(result.output.find("MPI_ABORT"), std::string::npos) << result.output;
}

std::size_t count_of(const std::string& text, const std::string& part)
{
  std::size_t count = 0;
  for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) count++;
  return count;
}

TEST(MultipleRanks, NarrowSubdomainsAreReportedOnce)
{
  // Contact cutoff 2 d_max + skin = 6e-4: subdomains of 1e-3 are 1.7 cutoffs, of 1.5e-3 are 2.5.
  const std::string launcher = "mpirun --allow-run-as-root --oversubscribe -np 2 ";
  const std::string warning = "MPI subdomains down to 0.001 wide, less than 2 contact cutoffs (0.0006)";
  const RunResult narrow = run_deck("narrow_subdomains", two_rank_deck("0.002"), launcher);
  EXPECT_EQ(narrow.exit_status, 0) << narrow.output;
  EXPECT_EQ(count_of(narrow.output, warning), 1u) << narrow.output;
  const RunResult wide = run_deck("wide_subdomains", two_rank_deck("0.003"), launcher);
  EXPECT_EQ(wide.exit_status, 0) << wide.output;
  EXPECT_EQ(count_of(wide.output, "contact cutoffs"), 0u) << wide.output;
}

}  // namespace
