// A dense polydisperse bed of rigid disks resting under gravity, built deterministically
// without LAMMPS, and one Moreau–Jean step of the solver core frozen at that state so that a
// benchmark can replay it as often as it likes.
//
// The bed is made as the scene makes it, by rain: disks are dropped one at a time into the
// lowest pocket near a random abscissa (touching two disks, or a disk and the floor), then the
// whole packing settles for a few steps under gravity with the solver core itself, so that
// contacts carry their weight and the warm-start impulses are those of a real step.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "cd/gauss_seidel.h"
#include "cd/step.h"
#include "cd/walls.h"

namespace testbed {

struct BedSpec {
  int disk_count = 4000;
  double mean_diameter = 5.0e-4;  // d (m)
  double polydispersity = 0.4;    // (dmax - dmin) / d, diameters uniform
  double cell_length = 45.0;      // periodic length in x, in d (the scene's default cell)
  double density = 2500.0;        // kg/m^2: disk mass pi r^2 rho
  double gravity = 9.81;          // m/s^2, along -y
  double slope = 0.0;             // degrees: gravity tilted towards +x, a chute (0: a bed at rest)
  double dt = 1.0e-5;             // s
  double theta = 0.5;
  double skin = 0.2;                           // neighbour pairs: gap below skin d (a LAMMPS size list)
  double alert = cd::default_alert_diameters;  // solved pairs: cd::is_candidate alert, in d
  double rain_window = 1.0;                    // a disk lands within this many d of its drop abscissa
  int settle_steps = 200;                      // Moreau–Jean steps under gravity after the rain
  double immobile_layer = 0.0;                 // d: disks centred below this height are immobile obstacles
  std::uint64_t seed = 20240601;
  cd::ContactLaw grain_law{0.5, 0.5};
  cd::ContactLaw wall_law{0.5, 0.5};  // the floor y = 0
  cd::SolverSettings solver{1.0e-4, 1000, cd::ConvergenceNorm::quadratic};
};

// A pair the neighbour list would hand to the fix: body b is a disk seen at its periodic image
// nearest to a (b_shift_x added to its x), or the floor (b = world body).
struct NeighbourPair {
  int a = 0;  // body index (disk k is body k + 1)
  int b = 0;
  double b_shift_x = 0.0;   // m
  cd::Local2 warm_impulse;  // impulse this pair carried at the end of the previous step (N s)
};

// Everything one step of the core reads, frozen at the predicted configuration x_m.
struct FrozenStep {
  cd::StepParameters step;
  cd::BodySet bodies;               // inertia, v_n, free velocity v_n + dt g
  std::vector<cd::Disk> predicted;  // x_m = x_n + (1 - theta) dt v_n, per disk
  std::vector<NeighbourPair> pairs;
  cd::ContactLaw grain_law;
  cd::Wall floor;
  cd::PeriodicBox box;
  double alert = 0.0;  // m: cd::is_candidate
};

// The frozen step as a host of cd::MoreauJeanStep: its neighbour pairs and floor contacts,
// offered in the order of frozen.pairs, each with the impulse it carried (warm_impulse), keyed
// {a, b}.
class FrozenPairs : public cd::StepHost {
 public:
  explicit FrozenPairs(const FrozenStep& frozen) : frozen_(frozen) {}
  void collect_pairs(const cd::PairReach& reach, double from_margin, double to_margin,
                     cd::StepContacts& contacts) override;

 private:
  const FrozenStep& frozen_;
};

// The frozen step's settings of cd::MoreauJeanStep: its theta and alert, the bed's solver, the
// pairs in the order offered.
cd::StepSettings step_settings(const FrozenStep& frozen, const cd::SolverSettings& solver, bool warm);

// The core's step before the solve (cd::MoreauJeanStep::prepare): the candidates of the frozen
// pairs, prepared, in the order offered, and (if warm) the impulses carried over. The caller
// applies those impulses to a copy of the free velocity and solves.
void prepare_contacts(const FrozenStep& frozen, bool warm, std::vector<cd::Contact>& contacts);

class GranularBed {
 public:
  explicit GranularBed(const BedSpec& spec);  // rains and settles

  // Advances the bed by one step with the core; returns the solver's report.
  cd::SolveReport step();
  // The method of the steps from now on (cd::make_solver), the carried impulses kept.
  void use_solver(const cd::SolverSettings& solver);

  // The next step, frozen (the bed does not move). Disks of the immobile layer are obstacles as
  // the fix makes atoms outside its group: zero inverse mass and inertia, at rest, and no pair
  // of two obstacles (nor an obstacle on the floor) is listed.
  FrozenStep freeze() const;

  const BedSpec& spec() const { return spec_; }
  const std::vector<cd::Disk>& disks() const { return disks_; }
  const std::vector<cd::BodyVelocity>& velocities() const { return velocity_; }  // per disk
  const std::vector<cd::SolveReport>& settle_reports() const { return settle_reports_; }
  double length_x() const { return length_x_; }
  double kinetic_energy() const;  // J, translation + spin (areal density rho)
  double max_speed() const;       // m/s

 private:
  void rain();
  void immobilise_layer(FrozenStep& frozen) const;
  std::vector<NeighbourPair> find_neighbour_pairs(const std::vector<cd::Disk>& at) const;

  BedSpec spec_;
  double length_x_ = 0.0;
  std::vector<cd::Disk> disks_;
  std::vector<cd::BodyVelocity> velocity_;
  std::vector<cd::BodyInertia> inertia_;
  std::unordered_map<std::uint64_t, cd::Local2> carried_;  // loaded pairs' impulses, by pair key
  cd::MoreauJeanStep moreau_jean_;
  std::vector<cd::SolveReport> settle_reports_;
};

}  // namespace testbed
