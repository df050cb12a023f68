// Coarse-graining kernels and the grids they are summed on (Weinhart, Thornton, Luding & Bokhove,
// Granular Matter 14 (2012) 289; Goldhirsch, Granular Matter 12 (2010) 239): a grain's mass, area
// or momentum spread around its centre by a kernel psi of integral 1, a contact's force spread
// along its branch vector by the kernel's line integral, so that the divergence of the
// coarse-grained contact stress is exactly the coarse-grained contact force density.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace cdpost {

// The kernel's shape; `width` is its standard deviation along one axis (input length units), so
// that both shapes of one width smooth alike. Gaussian: cut at 3 widths and renormalised. Lucy:
// psi = C (1 + 3 r/c)(1 - r/c)^3 for r < c, its range c = sqrt(56/5) width in 2D (3.35) and
// sqrt(21/2) width in 1D (3.24).
enum class KernelShape { gaussian, lucy };

class Kernel {
 public:
  // `dimensions`: 2 for a map, 1 for a profile along one axis (the kernel then spreads across
  // a line and the other axis is averaged over the box).
  Kernel(KernelShape shape, double width, int dimensions);
  KernelShape shape() const { return shape_; }
  double width() const { return width_; }
  double range() const { return range_; }  // the kernel is 0 beyond this distance
  // psi at distance r (1/length^dimensions).
  double value(double r) const;
  // 1D: the integral of psi from -infinity to u (0 below -range, 1 above range).
  double cumulative(double u) const;
  // 2D: the integral over s in [0, 1] of psi(|p - s l|), p the node seen from the segment's start
  // and l the segment (the branch vector), exact for the Gaussian, 16-point Gauss-Legendre on
  // each side of the foot of the perpendicular for Lucy.
  double segment(double px, double py, double lx, double ly) const;
  // 1D: the same along one axis, u the node seen from the start, l the segment's extent.
  double segment(double u, double l) const;
  // "Gaussian, width 0.0005 (standard deviation), cut at 3 widths" or Lucy's with its range.
  std::string describe(const std::string& length_unit) const;

 private:
  KernelShape shape_;
  double width_, range_;
  int dimensions_;
  double norm_;  // the constant C in front of the shape
};

// One axis of a grid: `cells` cells of equal size tiling [low, high), nodes at their centres;
// a periodic axis wraps distances and kernel supports across its ends.
struct GridAxis {
  double low = 0, high = 1;
  size_t cells = 1;
  bool periodic = false;
  double spacing() const { return (high - low) / double(cells); }
  double node(size_t k) const { return low + (double(k) + 0.5) * spacing(); }
  double length() const { return high - low; }
  // The shortest displacement from a to b along the axis (wrapped when periodic).
  double displacement(double a, double b) const;
};

// Sums of kernel-weighted quantities on the nodes of a map (nx x ny) or a profile (one axis; the
// other is averaged over `across`, the box's extent along it). Each node holds `components`
// numbers; add_point spreads values from a point, add_segment along a segment.
class KernelGrid {
 public:
  // Map: both axes. Profile: along dimension `along_dimension` (0: x, 1: y) only, divided by
  // `across`, the extent averaged over.
  KernelGrid(const Kernel& kernel, GridAxis x, GridAxis y, size_t components);
  KernelGrid(const Kernel& kernel, int along_dimension, GridAxis along, double across, size_t components);
  // Nodes at given positions (a polar grid's cell centres), none periodic, found through buckets
  // of the kernel's range.
  KernelGrid(const Kernel& kernel, std::vector<std::array<double, 2>> nodes, size_t components);

  size_t nodes() const { return values_.size() / components_; }
  size_t components() const { return components_; }
  bool is_profile() const { return profile_; }
  bool is_scattered() const { return !points_.empty(); }
  const GridAxis& axis(int k) const { return axes_[k]; }
  double value(size_t node, size_t component) const { return values_[node * components_ + component]; }
  // The node's position: a map's node (i, j) is i + nx j; a profile's coordinate is along axis 0;
  // scattered nodes where they were given.
  std::array<double, 2> position(size_t node) const;

  // Adds weights[c] psi(node - at) to component c of every node (at: x, y; a profile reads only
  // its axis's coordinate).
  void add_point(std::array<double, 2> at, const double* weights);
  // Adds weights[c] times the integral of psi(node - from - s l) over s in [0, 1].
  void add_segment(std::array<double, 2> from, std::array<double, 2> l, const double* weights);
  // values += other's times `factor` (same layout).
  void add_scaled(const KernelGrid& other, double factor);
  void clear();

 private:
  // The node indices along axis k within `range` of the interval [a, b] (wrapped when periodic).
  std::vector<size_t> nodes_near(int k, double a, double b) const;
  // Scattered nodes: adds weights times psi(node) for every node within range of the box
  // [x0, x1] x [y0, y1].
  template <typename Psi>
  void add_near(double x0, double x1, double y0, double y1, const double* weights, Psi psi);

  Kernel kernel_;
  std::array<GridAxis, 2> axes_;
  bool profile_;
  int along_ = 0;  // a profile's dimension
  double across_ = 1;
  size_t components_;
  std::vector<double> values_;
  std::vector<std::array<double, 2>> points_;  // scattered nodes
  GridAxis bucket_x_, bucket_y_;               // their buckets, a range wide
  std::vector<std::vector<size_t>> buckets_;
};

}  // namespace cdpost
