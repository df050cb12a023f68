#include "fix_contact_dynamics_region_walls.h"

#include <cmath>

#include "domain.h"
#include "error.h"
#include "region.h"
#include "utils.h"

using namespace LAMMPS_NS;

namespace {

// A region turns about its point and unit axis, which LAMMPS keeps protected. A pointer to a
// member named through a derived class reads them on any Region ([class.protected] restricts
// the naming, not the object).
struct RegionRotation : Region {
  static const double* pivot(const Region& region) { return region.*(&RegionRotation::point); }
  static const double* axis(const Region& region) { return region.*(&RegionRotation::runit); }
};

// A contact vector's out-of-plane part below this fraction of its length is round-off.
constexpr double in_plane_tolerance = 1.0e-9;

bool combines_regions(const Region& region)
{
  return utils::strmatch(region.style, "^union") || utils::strmatch(region.style, "^intersect");
}

}  // namespace

void RegionWalls::init()
{
  walls_.assign(settings_.size(), Wall{});
  for (int r = 0; r < count(); r++) {
    const std::string& id = settings_[r].region_id;
    const int index = domain->find_region(id);
    if (index < 0) error->all(FLERR, "Fix contact/dynamics: wall region {} does not exist", id);
    walls_[r].region = domain->regions[index];
    check_usable(*walls_[r].region, id);
  }
}

// The fix meets rigid regions in the plane: no shape that changes, no turn about an axis in the
// plane; combined regions only of regions that stand still (each moving part can be a wall of
// its own).
void RegionWalls::check_usable(const Region& region, const std::string& wall_region) const
{
  const std::string name = fmt::format("region {} ({})", region.id, region.style);
  const std::string in = region.id == wall_region ? "" : fmt::format(", part of wall region {},", wall_region);
  if (region.varshape)
    error->all(FLERR, "Fix contact/dynamics: {}{} changes its shape with variables; walls must be rigid", name, in);
  if (combines_regions(region)) {
    for (int k = 0; k < region.nregion; k++) {
      const Region& part = *domain->regions[region.list[k]];
      if (part.dynamic)
        error->all(FLERR,
                   "Fix contact/dynamics: {} combines moving region {}; give the moving region a wall region "
                   "keyword of its own",
                   name, part.id);
      check_usable(part, wall_region);
    }
    return;
  }
  if (region.rotateflag) {
    const double* axis = RegionRotation::axis(region);
    if (std::fabs(axis[0]) > in_plane_tolerance || std::fabs(axis[1]) > in_plane_tolerance)
      error->all(FLERR, "Fix contact/dynamics: {}{} rotates about an axis that is not along z", name, in);
  }
}

cd::WallPose RegionWalls::pose_of(const Region& region)
{
  return {region.moveflag ? region.dx : 0.0, region.moveflag ? region.dy : 0.0, region.rotateflag ? region.theta : 0.0};
}

void RegionWalls::place(Region& region, const cd::WallPose& pose)
{
  if (region.moveflag) region.dx = pose.dx, region.dy = pose.dy;
  if (region.rotateflag) region.theta = pose.angle;
}

void RegionWalls::record_start()
{
  for (Wall& wall : walls_) {
    if (!wall.region->dynamic) continue;
    wall.region->prematch();
    wall.start = wall.end = wall.at_solve = pose_of(*wall.region);
    wall.motion = {};
  }
}

void RegionWalls::begin_step(const cd::StepParameters& step)
{
  for (Wall& wall : walls_) {
    Region& region = *wall.region;
    if (!region.dynamic) continue;
    region.prematch();
    if (region.moveflag && region.dz != 0.0)
      error->all(FLERR, "Fix contact/dynamics: wall region {} moves along z (by {}); a 2D wall moves in the plane",
                 region.id, region.dz);
    wall.end = pose_of(region);
    wall.at_solve = cd::wall_at_solve(wall.start, wall.end, step);
    // LAMMPS turns about the axis (0, 0, +-1) through the pivot: a turn by theta is one of
    // axis_z theta counter-clockwise.
    cd::WallPose start = wall.start, end = wall.end;
    double pivot_x = 0.0, pivot_y = 0.0;
    if (region.rotateflag) {
      const double sense = RegionRotation::axis(region)[2];
      start.angle *= sense;
      end.angle *= sense;
      pivot_x = RegionRotation::pivot(region)[0];
      pivot_y = RegionRotation::pivot(region)[1];
    }
    wall.motion = cd::wall_motion(start, end, pivot_x, pivot_y, step);
    wall.start = wall.end;  // the next step's
  }
}

RegionWalls::AtSolve::AtSolve(RegionWalls& walls) : walls_(walls)
{
  for (Wall& wall : walls_.walls_)
    if (wall.region->dynamic) place(*wall.region, wall.at_solve);
}

RegionWalls::AtSolve::~AtSolve()
{
  for (Wall& wall : walls_.walls_)
    if (wall.region->dynamic) place(*wall.region, wall.end);
}

// A contact whose vector leaves the plane is a face the plane does not cross (a block's or a
// cylinder's ends: skipped by the caller) or a surface that meets the plane obliquely (a sphere
// centred off the plane), whose contacts a disk cannot have.
void RegionWalls::check_in_plane(const Region& region, double delx, double dely, double delz, double distance) const
{
  if (std::fabs(delz) <= in_plane_tolerance * distance) return;
  if (std::hypot(delx, dely) <= in_plane_tolerance * distance) return;
  error->one(FLERR,
             "Fix contact/dynamics: wall region {} meets the plane z = 0 obliquely (a contact normal with a z "
             "part); centre its spheres, cones and cylinders on z = 0",
             region.id);
}

const std::vector<RegionWalls::Touch>& RegionWalls::touches(int r, int body, const cd::Disk& disk, double gap_limit,
                                                            double advance)
{
  touches_.clear();
  Wall& wall = walls_[r];
  Region& region = *wall.region;
  const double approach_bound = advance * wall.motion.speed_bound(disk.x, disk.y, disk.radius + gap_limit);
  const int found = region.surface(disk.x, disk.y, 0.0, disk.radius + gap_limit + approach_bound);
  for (int c = 0; c < found; c++) {
    const Region::Contact& contact = region.contact[c];
    // LAMMPS's own r is not always set (a union's exterior): the distance from the vector.
    const double distance =
        std::sqrt(contact.delx * contact.delx + contact.dely * contact.dely + contact.delz * contact.delz);
    check_in_plane(region, contact.delx, contact.dely, contact.delz, distance);
    if (std::fabs(contact.delz) > in_plane_tolerance * distance) continue;  // a face parallel to the plane
    if (contact.iwall < 0 || contact.iwall >= faces_per_region)
      error->one(FLERR, "Fix contact/dynamics: wall region {} names face {}, beyond the {} a region may have",
                 region.id, contact.iwall, faces_per_region);
    Touch touch{cd::disk_world_geometry(body, disk, contact.delx, contact.dely, 0.0, 1.0), contact.iwall, 0.0};
    // The surface point touched moves with the region: the contact's image velocity.
    wall.motion.velocity_at(disk.x - contact.delx, disk.y - contact.dely, touch.geometry.image_vx,
                            touch.geometry.image_vy);
    touch.approach = advance * std::hypot(touch.geometry.image_vx, touch.geometry.image_vy);
    if (touch.geometry.gap > gap_limit + touch.approach) continue;
    touches_.push_back(touch);
  }
  return touches_;
}
