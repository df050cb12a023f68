// Coarse-grained fields (signal/coarse_graining.h, analysis/fields.h) on synthetic dumps, no
// LAMMPS: the kernels' integrals, the packing fraction of a uniform lattice, and the contact
// stress of a stacked lattice against the weight it carries.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "analysis/fields.h"
#include "io/line_source.h"
#include "signal/coarse_graining.h"
#include "signal/statistics.h"
#include "temp_files.h"

namespace cdpost {
namespace {

// Midpoint sum of psi over the plane (2D, by rings) or the line (1D).
double kernel_integral(const Kernel& kernel, int dimensions)
{
  const int steps = 200000;
  const double h = kernel.range() / steps;
  double sum = 0;
  for (int k = 0; k < steps; ++k) {
    const double r = (k + 0.5) * h;
    sum += kernel.value(r) * (dimensions == 2 ? 2 * M_PI * r : 2.0) * h;
  }
  return sum;
}

TEST(Fields, KernelsIntegrateToOneAndHaveTheirWidth)
{
  for (auto shape : {KernelShape::gaussian, KernelShape::lucy})
    for (int dims : {1, 2}) {
      const Kernel kernel(shape, 0.7, dims);
      EXPECT_NEAR(kernel_integral(kernel, dims), 1.0, 1e-9);
      // The variance along one axis is the width squared (a Gaussian cut at 3 widths: 0.9494 of it in
      // 2D, 0.9733 in 1D).
      const int steps = 200000;
      const double h = kernel.range() / steps;
      double second_moment = 0;
      for (int k = 0; k < steps; ++k) {
        const double r = (k + 0.5) * h;
        second_moment += kernel.value(r) * r * r * (dims == 2 ? M_PI * r : 2.0) * h;  // <x^2> = <r^2> / 2 in 2D
      }
      const double expected = shape == KernelShape::lucy ? 0.49 : (dims == 2 ? 0.49 * 0.949448 : 0.49 * 0.973337);
      EXPECT_NEAR(second_moment, expected, 1e-4 * expected)
          << (shape == KernelShape::lucy ? "lucy " : "gauss ") << dims;
    }
}

// The segment integrals against a fine midpoint sum along the segment.
TEST(Fields, SegmentIntegralsMatchQuadrature)
{
  for (auto shape : {KernelShape::gaussian, KernelShape::lucy}) {
    const Kernel plane(shape, 0.5, 2), line(shape, 0.5, 1);
    const double cases[][4] = {
        {0.3, 0.2, 1.0, 0.4}, {0.0, 0.0, 1.0, 0.0}, {1.2, -0.3, -0.8, 0.9}, {2.0, 1.5, 0.5, 0.5}};
    for (const auto& c : cases) {
      const int steps = 100000;
      double sum = 0, sum_1d = 0;
      for (int k = 0; k < steps; ++k) {
        const double s = (k + 0.5) / steps;
        sum += plane.value(std::hypot(c[0] - s * c[2], c[1] - s * c[3])) / steps;
        sum_1d += line.value(c[0] - s * c[2]) / steps;
      }
      EXPECT_NEAR(plane.segment(c[0], c[1], c[2], c[3]), sum, 1e-6 * (1 + sum));
      EXPECT_NEAR(line.segment(c[0], c[2]), sum_1d, 1e-6 * (1 + sum_1d));
    }
  }
}

struct Disk {
  long id;
  double x, y, vx, vy, radius;
};

std::string atoms_frame(long step, double lx, double ly, const char* boundary, const std::vector<Disk>& disks)
{
  std::ostringstream text;
  text.precision(12);
  text << "ITEM: TIMESTEP\n"
       << step << "\nITEM: NUMBER OF ATOMS\n"
       << disks.size() << "\nITEM: BOX BOUNDS " << boundary << "\n0 " << lx << "\n0 " << ly
       << "\n-0.5 0.5\nITEM: ATOMS id type x y vx vy radius\n";
  for (const auto& d : disks)
    text << d.id << " 1 " << d.x << ' ' << d.y << ' ' << d.vx << ' ' << d.vy << ' ' << d.radius << '\n';
  return text.str();
}

// A square lattice of spacing a filling a periodic box: phi = pi r^2 / a^2 everywhere.
std::vector<Disk> lattice(int nx, int ny, double a, double r, double vx = 0)
{
  std::vector<Disk> disks;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) disks.push_back({long(disks.size() + 1), (i + 0.5) * a, (j + 0.5) * a, vx, 0, r});
  return disks;
}

FieldsSettings lattice_settings(const std::string& dump, KernelShape shape, double width)
{
  FieldsSettings s;
  s.dump_path = dump;
  s.units = FieldUnits::si("test");
  s.kernel = shape;
  s.width = width;
  s.grain_density = 2500;
  return s;
}

// A lattice sum of the kernel differs from its integral by the kernel's Fourier transform at the
// reciprocal lattice (Poisson summation). The cut Gaussian's jump, e^{-4.5} = 1.1 % of its peak
// at 3 widths, ripples it by about that jump times the sites near the cut over those inside
// (~1/3 at a width of 2 spacings): 0.24 % measured on the map, 0.05 % on the profile, 0.4 %
// allowed. Lucy's kernel is smooth to its second derivative: 1e-5 and 5e-5 measured, 2e-4
// allowed. (At a width of one spacing the Gaussian's ripple is 0.6 %, Lucy's 0.14 %.)
TEST(Fields, PackingFractionOfAUniformLatticeIsKnown)
{
  const double a = 1e-3, r = 0.45e-3, expected = M_PI * r * r / (a * a);
  const auto dump = testing::write_file(testing::scratch_dir() / "lattice.dump",
                                        atoms_frame(0, 24 * a, 20 * a, "pp pp pp", lattice(24, 20, a, r, 0.2)) +
                                            atoms_frame(100, 24 * a, 20 * a, "pp pp pp", lattice(24, 20, a, r, 0.2)));
  for (auto shape : {KernelShape::gaussian, KernelShape::lucy}) {
    for (int along : {-1, 1}) {
      auto settings = lattice_settings(dump, shape, 2 * a);
      settings.along = along;
      settings.cells = along < 0 ? std::array<size_t, 2>{37, 29} : std::array<size_t, 2>{41, 0};
      const auto fields = compute_fields(settings);
      EXPECT_EQ(fields.frames, 2u);
      const auto& phi = fields.column("phi").values;
      const auto& ux = fields.column("ux").values;
      const auto& temperature = fields.column("T").values;
      double worst = 0;
      for (size_t k = 0; k < phi.size(); ++k) {
        worst = std::max(worst, std::abs(phi[k] / expected - 1));
        EXPECT_NEAR(ux[k], 0.2, 1e-12);
        EXPECT_NEAR(temperature[k], 0.0, 1e-12);
      }
      EXPECT_LT(worst, shape == KernelShape::lucy ? 2e-4 : 4e-3)
          << (shape == KernelShape::lucy ? "lucy" : "gauss") << " along " << along;
    }
  }
}

// A stack of touching disks (a = 2r) on a floor, x-periodic: each column carries its grains'
// weight; between the centres of rows k and k+1 the stress is (rows above k) m g / a. A kernel
// whose range is within a quarter row sees that constant exactly three quarters up a row: the
// profile to rounding; the map, averaged along x, to its nodes' midpoint sum (spacing 0.8 width).
TEST(Fields, ContactStressOfAStackIsTheWeightAbove)
{
  const double a = 1e-3, r = 0.5e-3, density = 2500, g = 9.81, dt = 1e-5;
  const int nx = 8, ny = 6;
  const double m = M_PI * r * r * density;
  const auto disks = lattice(nx, ny, a, r);
  std::ostringstream local;
  local.precision(12);
  local << "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ENTRIES\n"
        << nx * ny << "\nITEM: BOX BOUNDS pp fm pp\n0 " << nx * a << "\n0 " << ny * a
        << "\n-0.5 0.5\nITEM: ENTRIES f_cd[1] f_cd[2] f_cd[3] f_cd[4] f_cd[5] f_cd[6] f_cd[7]\n";
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const long id = 1 + i + nx * j;
      const double impulse = (ny - j) * m * g * dt;  // carries itself and the rows above
      if (j == 0) local << id << " 0 1 " << impulse << " 0 " << (i + 0.5) * a << " 0\n";
      else local << id << ' ' << id - nx << " 0 " << impulse << " 0 " << (i + 0.5) * a << ' ' << j * a << '\n';
    }
  const auto dir = testing::scratch_dir();
  const auto dump = testing::write_file(dir / "stack.dump", atoms_frame(0, nx * a, ny * a, "pp fm pp", disks));
  const auto contacts = testing::write_file(dir / "stack.contacts", local.str());
  for (auto shape : {KernelShape::gaussian, KernelShape::lucy}) {
    for (int along : {-1, 1}) {
      auto settings = lattice_settings(dump, shape, 0.05 * a);  // range 0.15 and 0.17 a
      settings.contacts_path = contacts;
      settings.timestep_size = dt;
      settings.along = along;
      settings.range = std::array<double, 2>{0.0, ny * a};
      const size_t per_row = along < 0 ? nx * 25 : 1;
      settings.cells = along < 0 ? std::array<size_t, 2>{per_row, ny * 2} : std::array<size_t, 2>{ny * 2, 0};
      const auto fields = compute_fields(settings);
      // The mean along x of the nodes at y = (k + 1/2) a / 2.
      auto row_mean = [&](const std::string& name, int k) {
        double sum = 0;
        for (size_t i = 0; i < per_row; ++i) sum += fields.column(name).values[k * per_row + i];
        return sum / double(per_row);
      };
      const double weight = ny * m * g / a, tolerance = (along < 0 ? 1e-3 : 1e-9) * weight;
      for (int j = 0; j < ny; ++j) {
        // Nodes at y = (j + 1/4) a and (j + 3/4) a: the second between the centres of rows j and j + 1.
        const double above = j + 1 < ny ? (ny - j - 1) * m * g / a : 0.0;
        EXPECT_NEAR(row_mean("s_yy", 2 * j + 1), above, tolerance) << "row " << j << " along " << along;
        EXPECT_NEAR(row_mean("s_xx", 2 * j + 1), 0.0, 1e-12 * weight);
        EXPECT_NEAR(row_mean("s_yx", 2 * j + 1), 0.0, 1e-12 * weight);
      }
      // At the first row's lower quarter the floor contacts' lines: all the weight.
      EXPECT_NEAR(row_mean("s_yy", 0), weight, tolerance) << "along " << along;
    }
  }
}

// Polar cells on a uniform lattice turning as a rigid body (v = Omega x r about the cells'
// centre): u_theta = Omega r and u_r = 0 to the lattice's ripple (a kernel-weighted centre of mass
// off the node), no shear rate, phi as on the map.
TEST(Fields, PolarCellsOfARigidRotation)
{
  const double a = 1e-3, r = 0.45e-3, omega = 3.0, expected = M_PI * r * r / (a * a);
  const int side = 40;
  const double centre = 0.5 * side * a;
  auto disks = lattice(side, side, a, r);
  for (auto& d : disks) d.vx = -omega * (d.y - centre), d.vy = omega * (d.x - centre);
  const auto dump = testing::write_file(testing::scratch_dir() / "turning.dump",
                                        atoms_frame(0, side * a, side * a, "ff ff pp", disks));
  auto settings = lattice_settings(dump, KernelShape::lucy, 2 * a);
  settings.polar = PolarCells{centre, centre, 2 * a, 12 * a, 10, 48};
  const auto fields = compute_fields(settings);
  const auto& radius = fields.column("r").values;
  const auto& phi = fields.column("phi").values;
  const auto& ur = fields.column("u_r").values;
  const auto& ut = fields.column("u_theta").values;
  const auto& rate = fields.column("gamma_dot").values;
  ASSERT_EQ(phi.size(), 480u);
  for (size_t k = 0; k < phi.size(); ++k) {
    EXPECT_NEAR(phi[k], expected, 2e-4 * expected) << k;
    EXPECT_NEAR(ut[k], omega * radius[k], 1e-3 * omega * 12 * a) << k;
    EXPECT_NEAR(ur[k], 0.0, 1e-3 * omega * 12 * a) << k;
    EXPECT_LT(rate[k], 0.02 * omega) << k;
  }
}

TEST(Fields, ATruncatedDumpFailsNamingItsFileAndLine)
{
  auto text = atoms_frame(0, 0.01, 0.01, "pp pp pp", lattice(10, 10, 1e-3, 4e-4));
  text.resize(text.size() - 40);
  const auto dump = testing::write_file(testing::scratch_dir() / "cut.dump", text);
  try {
    compute_fields(lattice_settings(dump, KernelShape::gaussian, 1e-3));
    FAIL() << "a truncated dump was read";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(dump + ":"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace cdpost
