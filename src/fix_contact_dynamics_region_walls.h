// LAMMPS regions as rigid walls of fix contact/dynamics (wall region ID mu e). A grain meets a
// region's surface from the side the region's `side` gives (inside a drum or a hopper, outside an
// obstacle), as fix wall/gran/region's grains do. A region that moves or turns (region ... move,
// rotate with variables) is met where it stands at the grains' instant x_m, with the velocity of
// the surface point touched (its pose's travel over the step), so a turning drum drags its grains
// by friction. The region's poses come from LAMMPS at every step; nothing of them is restarted.
#pragma once

#include <string>
#include <vector>

#include "cd/contact.h"
#include "cd/contact_geometry.h"
#include "cd/walls.h"
#include "pointers.h"

namespace LAMMPS_NS {
class Region;

struct RegionWallSetting {
  std::string region_id;
  cd::ContactLaw law;
  int number = 0;  // 1-based, among all the fix's walls in the order given
};

class RegionWalls : protected Pointers {
 public:
  // Face ids a region may name (LAMMPS's iwall, below its cmax): a contact's warm-start key is
  // its region's slot plus its face.
  static constexpr int faces_per_region = 4096;

  RegionWalls(LAMMPS* lmp, const std::vector<RegionWallSetting>& settings) : Pointers(lmp), settings_(settings) {}

  int count() const { return static_cast<int>(settings_.size()); }
  const RegionWallSetting& setting(int r) const { return settings_[r]; }

  // The regions found and checked: one error line names a region the fix cannot use.
  void init();
  // The poses now start the next step (at a run's setup and after every step).
  void record_start();
  // The poses at the step's end (LAMMPS's variables at this timestep) and the motion over the
  // step, met at x_m (cd::wall_at_solve, cd::wall_motion).
  void begin_step(const cd::StepParameters& step);

  // A disk's contact with one region wall; the geometry's image velocity is the surface's.
  struct Touch {
    cd::ContactGeometry geometry;
    int face;         // LAMMPS's iwall
    double approach;  // how far the surface may come in the rest of the step (m)
  };
  // The contacts of `disk` (body `body`) with region wall r whose gap is at most `gap_limit`
  // plus the surface's approach in the rest of the step (its speed bound over `advance`
  // seconds). Where the regions stand: at x_m within an AtSolve's life, at the step's end
  // outside it. Valid until the next call.
  const std::vector<Touch>& touches(int r, int body, const cd::Disk& disk, double gap_limit, double advance);

  // While it lives, every moving region of the walls stands where the step meets it.
  class AtSolve {
   public:
    explicit AtSolve(RegionWalls& walls);
    ~AtSolve();
    AtSolve(const AtSolve&) = delete;
    AtSolve& operator=(const AtSolve&) = delete;

   private:
    RegionWalls& walls_;
  };

 private:
  struct Wall {
    Region* region = nullptr;
    cd::WallPose start, end, at_solve;
    cd::SurfaceMotion motion;  // over the step; zero for a region that does not move
    bool moves = false;
  };

  void check_usable(const Region& region, const std::string& wall_region) const;
  void check_in_plane(const Region& region, double delx, double dely, double delz, double distance) const;
  static cd::WallPose pose_of(const Region& region);
  static void place(Region& region, const cd::WallPose& pose);

  const std::vector<RegionWallSetting>& settings_;
  std::vector<Wall> walls_;
  std::vector<Touch> touches_;
};

}  // namespace LAMMPS_NS
