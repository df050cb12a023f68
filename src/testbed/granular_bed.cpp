#include "testbed/granular_bed.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

namespace testbed {

namespace {

// Rounding slack of the rain's contact geometry: a disk placed against two others touches them
// to a few ulps, which must not read as an overlap.
constexpr double touch_slack = 1.0e-9;

// Uniform in [0, 1) from the top 53 bits: the same sequence with every standard library.
double uniform01(std::mt19937_64& rng)
{
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

double nearest_image(double dx, double length)
{
  return dx - length * std::nearbyint(dx / length);
}

std::uint64_t pair_key(int body_a, int body_b)
{
  return (static_cast<std::uint64_t>(body_a) << 32) | static_cast<std::uint32_t>(body_b);
}

// Disks binned in square cells at least as wide as the largest contact distance, periodic in
// x, growing upward in y >= 0: the 3 x 3 cells around a disk hold every disk it can touch.
class CellGrid {
 public:
  CellGrid(double length_x, double min_cell)
      : columns_(std::max(3, static_cast<int>(length_x / min_cell))),
        width_(length_x / columns_),
        height_(min_cell),
        top_(columns_, -1)
  {
  }

  int column(double x) const
  {
    const int c = static_cast<int>(std::floor(x / width_)) % columns_;
    return c < 0 ? c + columns_ : c;
  }
  int row(double y) const { return std::max(0, static_cast<int>(std::floor(y / height_))); }
  int columns() const { return columns_; }
  double cell_width() const { return width_; }
  int top_row(int column) const { return top_[column]; }

  void insert(int index, const cd::Disk& disk)
  {
    const int c = column(disk.x), r = row(disk.y);
    if (r >= rows_) {
      rows_ = r + 1;
      cells_.resize(static_cast<std::size_t>(rows_) * columns_);
    }
    cells_[static_cast<std::size_t>(r) * columns_ + c].push_back(index);
    top_[c] = std::max(top_[c], r);
  }

  const std::vector<int>& cell(int column, int row) const
  {
    static const std::vector<int> none;
    if (row < 0 || row >= rows_) return none;
    const int c = ((column % columns_) + columns_) % columns_;
    return cells_[static_cast<std::size_t>(row) * columns_ + c];
  }

  template <class Visit>
  void for_each_near(double x, double y, Visit visit) const
  {
    const int c = column(x), r = row(y);
    for (int dr = -1; dr <= 1; dr++)
      for (int dc = -1; dc <= 1; dc++)
        for (int k : cell(c + dc, r + dr)) visit(k);
  }

 private:
  int columns_;
  double width_;
  double height_;
  int rows_ = 0;
  std::vector<int> top_;
  std::vector<std::vector<int>> cells_;
};

// Where a disk of radius r rests on disks i and j (j at its image nearest to i): the upper
// point at distance r_i + r from i and r_j + r from j, stable only between the two centres.
bool rest_on_pair(const cd::Disk& i, const cd::Disk& j, double r, double& x, double& y)
{
  const double dx = j.x - i.x, dy = j.y - i.y;
  const double distance = std::sqrt(dx * dx + dy * dy);
  const double reach_i = i.radius + r, reach_j = j.radius + r;
  if (distance >= reach_i + reach_j || distance <= std::abs(reach_i - reach_j)) return false;
  const double along = (reach_i * reach_i - reach_j * reach_j + distance * distance) / (2.0 * distance);
  const double across = std::sqrt(reach_i * reach_i - along * along);
  const double side = dx >= 0.0 ? 1.0 : -1.0;  // picks the intersection above the line i-j
  x = i.x + (along * dx - side * across * dy) / distance;
  y = i.y + (along * dy + side * across * dx) / distance;
  return x > std::min(i.x, j.x) && x < std::max(i.x, j.x);
}

}  // namespace

void FrozenPairs::collect_pairs(const cd::PairReach& reach, double from_margin, double to_margin,
                                cd::StepContacts& contacts)
{
  for (const NeighbourPair& pair : frozen_.pairs) {
    const cd::Disk& disk_a = frozen_.predicted[pair.a - 1];
    const cd::PairKey key{pair.a, pair.b};
    if (pair.b == cd::world_body) {
      const double reach_a = reach.reach(pair.a);
      const auto touch = cd::wall_contact(frozen_.floor, pair.a, disk_a, reach_a + to_margin, frozen_.box);
      if (!touch || !reach.wall_in_look(pair.a, touch->geometry.gap, from_margin)) continue;
      contacts.offer(touch->geometry, frozen_.floor.law, key, pair.warm_impulse);
      continue;
    }
    cd::Disk disk_b = frozen_.predicted[pair.b - 1];
    disk_b.x += pair.b_shift_x;
    if (!reach.in_look(pair.a, disk_a, pair.b, disk_b, from_margin, to_margin)) continue;
    contacts.offer(cd::disk_disk_geometry(pair.a, disk_a, pair.b, disk_b), frozen_.grain_law, key, pair.warm_impulse);
  }
}

namespace {

cd::StepSettings step_settings(double theta, double alert, const cd::SolverSettings& solver, bool warm)
{
  cd::StepSettings settings;
  settings.theta = theta;
  settings.solver = solver;
  settings.alert = alert;
  settings.warm_start = warm;
  settings.order = cd::ContactOrder::as_offered;
  return settings;
}

}  // namespace

cd::StepSettings step_settings(const FrozenStep& frozen, const cd::SolverSettings& solver, bool warm)
{
  return step_settings(frozen.step.theta, frozen.alert, solver, warm);
}

void prepare_contacts(const FrozenStep& frozen, bool warm, std::vector<cd::Contact>& contacts)
{
  FrozenPairs host(frozen);
  cd::MoreauJeanStep moreau_jean(step_settings(frozen, {}, warm));
  moreau_jean.prepare(frozen.bodies, frozen.step.dt, host);
  contacts = moreau_jean.contacts().solved;
}

GranularBed::GranularBed(const BedSpec& spec)
    : spec_(spec),
      length_x_(spec.cell_length * spec.mean_diameter),
      moreau_jean_(step_settings(spec.theta, spec.alert * spec.mean_diameter, spec.solver, true))
{
  rain();
  velocity_.assign(disks_.size(), cd::BodyVelocity{});
  inertia_.resize(disks_.size());
  for (std::size_t k = 0; k < disks_.size(); k++) {
    const double r = disks_[k].radius;
    inertia_[k] = cd::disk_inertia(cd::disk_mass(r, spec_.density), r);
  }
  for (int s = 0; s < spec_.settle_steps; s++) settle_reports_.push_back(step());
}

void GranularBed::rain()
{
  const double d = spec_.mean_diameter;
  const double r_max = 0.5 * d * (1.0 + 0.5 * spec_.polydispersity);
  std::mt19937_64 rng(spec_.seed);
  CellGrid grid(length_x_, 2.0 * r_max);
  disks_.clear();
  disks_.reserve(spec_.disk_count);

  std::vector<int> surface;
  for (int n = 0; n < spec_.disk_count; n++) {
    const double r = 0.5 * d * (1.0 + spec_.polydispersity * (uniform01(rng) - 0.5));
    const double drop_x = uniform01(rng) * length_x_;

    auto overlaps = [&](double x, double y) {
      bool hit = false;
      grid.for_each_near(x, y, [&](int k) {
        const double dx = nearest_image(x - disks_[k].x, length_x_), dy = y - disks_[k].y;
        const double contact = (r + disks_[k].radius) * (1.0 - touch_slack);
        hit = hit || dx * dx + dy * dy < contact * contact;
      });
      return hit;
    };

    cd::Disk landed{0.0, std::numeric_limits<double>::infinity(), r};
    auto consider = [&](double x, double y, double window) {
      if (y < r * (1.0 - touch_slack) || y >= landed.y) return;
      if (std::abs(nearest_image(x - drop_x, length_x_)) > window || overlaps(x, y)) return;
      landed.x = x;
      landed.y = y;
    };

    // The lowest pocket within the window, among disks near the local surface; widen the
    // window if every pocket there is blocked.
    for (double window = spec_.rain_window * d; !std::isfinite(landed.y); window *= 2.0) {
      if (window > 2.0 * length_x_) throw std::runtime_error("granular bed: no pocket for disk " + std::to_string(n));
      const double reach = window + r + r_max;
      const int first = grid.column(drop_x - reach);
      const int span = std::min(grid.columns(), static_cast<int>(std::ceil(2.0 * reach / grid.cell_width())) + 2);
      // Each column's top cells, down to below its neighbours' tops: a pocket's supports.
      surface.clear();
      const int columns = grid.columns();
      for (int c = first; c < first + span; c++) {
        const int top = grid.top_row(c % columns);
        const int lowest = std::min({grid.top_row((c + columns - 1) % columns), top, grid.top_row((c + 1) % columns)});
        for (int row = lowest - 2; row <= top; row++)
          for (int k : grid.cell(c, row)) surface.push_back(k);
      }

      consider(drop_x, r, window);
      for (std::size_t s = 0; s < surface.size(); s++) {
        cd::Disk i = disks_[surface[s]];
        i.x = drop_x + nearest_image(i.x - drop_x, length_x_);
        const double height = i.y - r, reach_i = i.radius + r;
        if (std::abs(height) < reach_i) {
          const double side = std::sqrt(reach_i * reach_i - height * height);
          consider(i.x - side, r, window);
          consider(i.x + side, r, window);
        }
        for (std::size_t t = s + 1; t < surface.size(); t++) {
          cd::Disk j = disks_[surface[t]];
          j.x = i.x + nearest_image(j.x - i.x, length_x_);
          double x, y;
          if (rest_on_pair(i, j, r, x, y)) consider(x, y, window);
        }
      }
    }
    landed.x -= length_x_ * std::floor(landed.x / length_x_);
    grid.insert(n, landed);
    disks_.push_back(landed);
  }
}

std::vector<NeighbourPair> GranularBed::find_neighbour_pairs(const std::vector<cd::Disk>& at) const
{
  const double d = spec_.mean_diameter;
  const double r_max = 0.5 * d * (1.0 + 0.5 * spec_.polydispersity);
  const double skin = spec_.skin * d;
  CellGrid grid(length_x_, 2.0 * r_max + skin);
  for (std::size_t k = 0; k < at.size(); k++) {
    cd::Disk wrapped = at[k];
    wrapped.x -= length_x_ * std::floor(wrapped.x / length_x_);
    wrapped.y = std::max(wrapped.y, 0.0);
    grid.insert(static_cast<int>(k), wrapped);
  }

  std::vector<NeighbourPair> pairs, walls;
  for (std::size_t i = 0; i < at.size(); i++) {
    const cd::Disk& a = at[i];
    const double wrapped_x = a.x - length_x_ * std::floor(a.x / length_x_);
    grid.for_each_near(wrapped_x, std::max(a.y, 0.0), [&](int j) {
      if (j <= static_cast<int>(i)) return;
      const cd::Disk& b = at[j];
      const double dx = nearest_image(a.x - b.x, length_x_), dy = a.y - b.y;
      const double reach = a.radius + b.radius + skin;
      if (dx * dx + dy * dy >= reach * reach) return;
      NeighbourPair c;
      c.a = static_cast<int>(i) + 1;
      c.b = j + 1;
      c.b_shift_x = (a.x - dx) - b.x;
      pairs.push_back(c);
    });
    if (a.y - a.radius < skin) {
      NeighbourPair c;
      c.a = static_cast<int>(i) + 1;
      c.b = cd::world_body;
      walls.push_back(c);
    }
  }
  // Pairs in the order of their first disk, then the wall contacts, as the fix collects them.
  pairs.insert(pairs.end(), walls.begin(), walls.end());
  return pairs;
}

void GranularBed::immobilise_layer(FrozenStep& frozen) const
{
  const double height = spec_.immobile_layer * spec_.mean_diameter;
  auto obstacle = [&](int body) { return body == cd::world_body || frozen.predicted[body - 1].y < height; };
  const auto dropped = std::remove_if(frozen.pairs.begin(), frozen.pairs.end(),
                                      [&](const NeighbourPair& p) { return obstacle(p.a) && obstacle(p.b); });
  frozen.pairs.erase(dropped, frozen.pairs.end());
  for (std::size_t k = 0; k < frozen.predicted.size(); k++)
    if (obstacle(static_cast<int>(k) + 1)) {
      frozen.bodies.inertia[1 + k] = {};
      frozen.bodies.start_velocity[1 + k] = {};
      frozen.bodies.velocity[1 + k] = {};
    }
}

FrozenStep GranularBed::freeze() const
{
  FrozenStep frozen;
  frozen.step = {spec_.dt, spec_.theta};
  const int count = static_cast<int>(disks_.size());
  const double slope = spec_.slope * std::acos(-1.0) / 180.0;
  frozen.bodies.reset(1 + count);
  frozen.predicted = disks_;
  for (int k = 0; k < count; k++) {
    frozen.bodies.inertia[1 + k] = inertia_[k];
    frozen.bodies.start_velocity[1 + k] = velocity_[k];
    const double weight = spec_.gravity / inertia_[k].inv_mass;
    frozen.bodies.velocity[1 + k] = cd::free_velocity(velocity_[k], inertia_[k], weight * std::sin(slope),
                                                      -weight * std::cos(slope), 0.0, spec_.dt);
    const cd::Displacement lead = cd::predicted_motion(velocity_[k], frozen.step);
    frozen.predicted[k].x += lead.dx;
    frozen.predicted[k].y += lead.dy;
  }
  frozen.pairs = find_neighbour_pairs(frozen.predicted);
  immobilise_layer(frozen);
  for (NeighbourPair& c : frozen.pairs) {
    const auto carried = carried_.find(pair_key(c.a, c.b));
    if (carried != carried_.end()) c.warm_impulse = carried->second;
  }
  frozen.grain_law = spec_.grain_law;
  frozen.floor.shape = cd::Wall::Shape::line;
  frozen.floor.ax = 0.0;
  frozen.floor.bx = length_x_;  // normal to the left of a -> b: +y
  frozen.floor.law = spec_.wall_law;
  frozen.box.periodic_x = true;
  frozen.box.length_x = length_x_;
  frozen.alert = spec_.alert * spec_.mean_diameter;
  return frozen;
}

cd::SolveReport GranularBed::step()
{
  const FrozenStep frozen = freeze();
  FrozenPairs host(frozen);
  cd::BodySet bodies = frozen.bodies;
  const cd::StepReport report = moreau_jean_.solve(bodies, frozen.step.dt, host);
  carried_.clear();
  moreau_jean_.contacts().for_each_loaded([&](const cd::PairKey& key, const cd::Contact& contact, double) {
    carried_[pair_key(key.row, static_cast<int>(key.partner))] = contact.impulse;
  });
  const cd::StepParameters step = frozen.step;
  for (std::size_t k = 0; k < disks_.size(); k++) {
    velocity_[k] = bodies.velocity[1 + k];
    const cd::Displacement shift = cd::corrected_motion(velocity_[k], step);
    cd::Disk& disk = disks_[k];
    disk.x = frozen.predicted[k].x + shift.dx;
    disk.y = frozen.predicted[k].y + shift.dy;
    disk.x -= length_x_ * std::floor(disk.x / length_x_);
  }
  return report.solve;
}

void GranularBed::use_solver(const cd::SolverSettings& solver)
{
  spec_.solver = solver;
  moreau_jean_ = cd::MoreauJeanStep(step_settings(spec_.theta, spec_.alert * spec_.mean_diameter, solver, true));
}

double GranularBed::kinetic_energy() const
{
  double energy = 0.0;
  for (std::size_t k = 0; k < disks_.size(); k++) {
    const cd::BodyVelocity& v = velocity_[k];
    energy +=
        0.5 * (v.vx * v.vx + v.vy * v.vy) / inertia_[k].inv_mass + 0.5 * v.spin * v.spin / inertia_[k].inv_inertia;
  }
  return energy;
}

double GranularBed::max_speed() const
{
  double fastest = 0.0;
  for (const cd::BodyVelocity& v : velocity_) fastest = std::max(fastest, std::hypot(v.vx, v.vy));
  return fastest;
}

}  // namespace testbed
