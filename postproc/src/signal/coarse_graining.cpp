#include "signal/coarse_graining.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace cdpost {

namespace {

constexpr double kGaussianCut = 3;  // widths
// 8-point Gauss-Legendre on [-1, 1]: nodes and weights of the positive half.
constexpr double kLegendreNode[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
constexpr double kLegendreWeight[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};

// The Lucy shape (1 + 3x)(1 - x)^3 at x = r / c < 1, and its integral from 0 to x.
double lucy_shape(double x)
{
  const double rest = 1 - x;
  return (1 + 3 * x) * rest * rest * rest;
}
double lucy_shape_integral(double x)
{
  return x * (1 + x * x * (-2 + x * (2 - 0.6 * x)));
}

}  // namespace

Kernel::Kernel(KernelShape shape, double width, int dimensions) : shape_(shape), width_(width), dimensions_(dimensions)
{
  if (!(width > 0)) throw std::invalid_argument("kernel width must be positive");
  if (dimensions != 1 && dimensions != 2) throw std::invalid_argument("kernels are 1D or 2D");
  if (shape == KernelShape::gaussian) {
    range_ = kGaussianCut * width;
    norm_ = dimensions == 2 ? 1 / (2 * M_PI * width * width * (1 - std::exp(-0.5 * kGaussianCut * kGaussianCut)))
                            : 1 / (std::sqrt(2 * M_PI) * width * std::erf(kGaussianCut / std::sqrt(2.0)));
  } else {
    // Range from the variance: <x^2> = 5 c^2 / 56 per axis in 2D, 2 c^2 / 21 in 1D.
    range_ = dimensions == 2 ? std::sqrt(56.0 / 5.0) * width : std::sqrt(21.0 / 2.0) * width;
    norm_ = dimensions == 2 ? 5 / (M_PI * range_ * range_) : 5 / (4 * range_);
  }
}

double Kernel::value(double r) const
{
  r = std::abs(r);
  if (r >= range_) return 0;
  if (shape_ == KernelShape::gaussian) return norm_ * std::exp(-0.5 * r * r / (width_ * width_));
  return norm_ * lucy_shape(r / range_);
}

double Kernel::cumulative(double u) const
{
  if (u <= -range_) return 0;
  if (u >= range_) return 1;
  if (shape_ == KernelShape::gaussian)
    return 0.5 + 0.5 * std::erf(u / (std::sqrt(2.0) * width_)) / std::erf(kGaussianCut / std::sqrt(2.0));
  const double half = norm_ * range_ * lucy_shape_integral(std::abs(u) / range_);
  return u < 0 ? 0.5 - half : 0.5 + half;
}

double Kernel::segment(double u, double l) const
{
  if (std::abs(l) < 1e-9 * width_) return value(u);
  return (cumulative(u) - cumulative(u - l)) / l;
}

double Kernel::segment(double px, double py, double lx, double ly) const
{
  const double length = std::hypot(lx, ly);
  if (length < 1e-9 * width_) return value(std::hypot(px, py));
  const double along = (px * lx + py * ly) / length;  // the node's foot on the segment's line
  const double across2 = std::max(0.0, px * px + py * py - along * along);
  if (across2 >= range_ * range_) return 0;
  const double half_chord = std::sqrt(range_ * range_ - across2);
  const double begin = std::max(0.0, along - half_chord), end = std::min(length, along + half_chord);
  if (!(end > begin)) return 0;
  if (shape_ == KernelShape::gaussian) {
    const double scale = std::sqrt(2.0) * width_;
    return norm_ * std::exp(-0.5 * across2 / (width_ * width_)) * width_ * std::sqrt(M_PI / 2) *
           (std::erf((end - along) / scale) - std::erf((begin - along) / scale)) / length;
  }
  // Lucy's r = sqrt(across^2 + t^2) has a kink at the foot (t = 0) when across is 0: integrate
  // on each side of it.
  auto piece = [&](double a, double b) {
    if (!(b > a)) return 0.0;
    const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
    double sum = 0;
    for (int k = 0; k < 4; ++k)
      for (double sign : {-1.0, 1.0}) {
        const double t = mid + sign * half * kLegendreNode[k] - along;
        sum += kLegendreWeight[k] * value(std::sqrt(across2 + t * t));
      }
    return sum * half;
  };
  const double foot = std::clamp(along, begin, end);
  return (piece(begin, foot) + piece(foot, end)) / length;
}

std::string Kernel::describe(const std::string& length_unit) const
{
  std::ostringstream text;
  text.precision(4);
  if (shape_ == KernelShape::gaussian)
    text << "Gaussian kernel, width " << width_ << " " << length_unit << " (standard deviation), cut at "
         << kGaussianCut << " widths";
  else
    text << "Lucy kernel, width " << width_ << " " << length_unit << " (standard deviation along an axis), range "
         << range_ << " " << length_unit;
  return text.str();
}

double GridAxis::displacement(double a, double b) const
{
  double d = b - a;
  if (periodic) d -= length() * std::round(d / length());
  return d;
}

KernelGrid::KernelGrid(const Kernel& kernel, GridAxis x, GridAxis y, size_t components)
    : kernel_(kernel),
      axes_{x, y},
      profile_(false),
      components_(components),
      values_(x.cells * y.cells * components, 0.0)
{
}

KernelGrid::KernelGrid(const Kernel& kernel, int along_dimension, GridAxis along, double across, size_t components)
    : kernel_(kernel),
      axes_{along, GridAxis{}},
      profile_(true),
      along_(along_dimension),
      across_(across),
      components_(components),
      values_(along.cells * components, 0.0)
{
}

KernelGrid::KernelGrid(const Kernel& kernel, std::vector<std::array<double, 2>> nodes, size_t components)
    : kernel_(kernel),
      profile_(false),
      components_(components),
      values_(nodes.size() * components, 0.0),
      points_(std::move(nodes))
{
  if (points_.empty()) throw std::invalid_argument("no node");
  double low[2] = {points_[0][0], points_[0][1]}, high[2] = {low[0], low[1]};
  for (const auto& p : points_)
    for (int k = 0; k < 2; ++k) low[k] = std::min(low[k], p[k]), high[k] = std::max(high[k], p[k]);
  const double size = kernel.range();
  auto axis = [&](int k) {
    const auto cells = static_cast<size_t>(std::floor((high[k] - low[k]) / size)) + 1;
    return GridAxis{low[k], low[k] + double(cells) * size, cells, false};
  };
  bucket_x_ = axis(0), bucket_y_ = axis(1);
  buckets_.resize(bucket_x_.cells * bucket_y_.cells);
  for (size_t n = 0; n < points_.size(); ++n) {
    const auto i = std::min(bucket_x_.cells - 1, static_cast<size_t>((points_[n][0] - bucket_x_.low) / size));
    const auto j = std::min(bucket_y_.cells - 1, static_cast<size_t>((points_[n][1] - bucket_y_.low) / size));
    buckets_[i + bucket_x_.cells * j].push_back(n);
  }
}

template <typename Psi>
void KernelGrid::add_near(double x0, double x1, double y0, double y1, const double* weights, Psi psi)
{
  const double size = kernel_.range();
  auto index_range = [&](const GridAxis& axis, double a, double b) {
    const long first = std::max(0L, static_cast<long>(std::floor((a - size - axis.low) / size)));
    const long last = std::min(long(axis.cells) - 1, static_cast<long>(std::floor((b + size - axis.low) / size)));
    return std::make_pair(first, last);
  };
  const auto [i0, i1] = index_range(bucket_x_, x0, x1);
  const auto [j0, j1] = index_range(bucket_y_, y0, y1);
  for (long j = j0; j <= j1; ++j)
    for (long i = i0; i <= i1; ++i)
      for (size_t n : buckets_[size_t(i) + bucket_x_.cells * size_t(j)]) {
        const double value = psi(points_[n]);
        if (value == 0) continue;
        for (size_t m = 0; m < components_; ++m) values_[n * components_ + m] += weights[m] * value;
      }
}

std::array<double, 2> KernelGrid::position(size_t node) const
{
  if (!points_.empty()) return points_[node];
  if (profile_) return {axes_[0].node(node), 0.0};
  return {axes_[0].node(node % axes_[0].cells), axes_[1].node(node / axes_[0].cells)};
}

std::vector<size_t> KernelGrid::nodes_near(int k, double a, double b) const
{
  const GridAxis& axis = axes_[k];
  const double h = axis.spacing(), reach = kernel_.range();
  long first = static_cast<long>(std::floor((a - reach - axis.low) / h - 0.5));
  long last = static_cast<long>(std::ceil((b + reach - axis.low) / h - 0.5));
  const long cells = static_cast<long>(axis.cells);
  std::vector<size_t> found;
  if (axis.periodic) {
    if (last - first + 1 >= cells) first = 0, last = cells - 1;
    for (long i = first; i <= last; ++i) found.push_back(static_cast<size_t>(((i % cells) + cells) % cells));
  } else {
    for (long i = std::max(0L, first); i <= std::min(cells - 1, last); ++i) found.push_back(static_cast<size_t>(i));
  }
  return found;
}

void KernelGrid::add_point(std::array<double, 2> at, const double* weights)
{
  if (!points_.empty()) {
    add_near(at[0], at[0], at[1], at[1], weights, [&](const std::array<double, 2>& node) {
      return kernel_.value(std::hypot(node[0] - at[0], node[1] - at[1]));
    });
    return;
  }
  if (profile_) {
    const double c = at[along_];
    for (size_t i : nodes_near(0, c, c)) {
      const double psi = kernel_.value(axes_[0].displacement(c, axes_[0].node(i))) / across_;
      if (psi == 0) continue;
      for (size_t m = 0; m < components_; ++m) values_[i * components_ + m] += weights[m] * psi;
    }
    return;
  }
  const auto near_x = nodes_near(0, at[0], at[0]);
  for (size_t j : nodes_near(1, at[1], at[1])) {
    const double dy = axes_[1].displacement(at[1], axes_[1].node(j));
    for (size_t i : near_x) {
      const double psi = kernel_.value(std::hypot(axes_[0].displacement(at[0], axes_[0].node(i)), dy));
      if (psi == 0) continue;
      double* node = &values_[(i + axes_[0].cells * j) * components_];
      for (size_t m = 0; m < components_; ++m) node[m] += weights[m] * psi;
    }
  }
}

void KernelGrid::add_segment(std::array<double, 2> from, std::array<double, 2> l, const double* weights)
{
  if (!points_.empty()) {
    add_near(std::min(from[0], from[0] + l[0]), std::max(from[0], from[0] + l[0]), std::min(from[1], from[1] + l[1]),
             std::max(from[1], from[1] + l[1]), weights, [&](const std::array<double, 2>& node) {
               return kernel_.segment(node[0] - from[0], node[1] - from[1], l[0], l[1]);
             });
    return;
  }
  if (profile_) {
    const double a = from[along_], extent = l[along_];
    for (size_t i : nodes_near(0, std::min(a, a + extent), std::max(a, a + extent))) {
      // The node seen from the segment's middle, then from its start: the right image when wrapped.
      const double u = axes_[0].displacement(a + 0.5 * extent, axes_[0].node(i)) + 0.5 * extent;
      const double psi = kernel_.segment(u, extent) / across_;
      if (psi == 0) continue;
      for (size_t m = 0; m < components_; ++m) values_[i * components_ + m] += weights[m] * psi;
    }
    return;
  }
  const double mid_x = from[0] + 0.5 * l[0], mid_y = from[1] + 0.5 * l[1];
  const auto near_x = nodes_near(0, std::min(from[0], from[0] + l[0]), std::max(from[0], from[0] + l[0]));
  for (size_t j : nodes_near(1, std::min(from[1], from[1] + l[1]), std::max(from[1], from[1] + l[1]))) {
    const double py = axes_[1].displacement(mid_y, axes_[1].node(j)) + 0.5 * l[1];
    for (size_t i : near_x) {
      const double px = axes_[0].displacement(mid_x, axes_[0].node(i)) + 0.5 * l[0];
      const double psi = kernel_.segment(px, py, l[0], l[1]);
      if (psi == 0) continue;
      double* node = &values_[(i + axes_[0].cells * j) * components_];
      for (size_t m = 0; m < components_; ++m) node[m] += weights[m] * psi;
    }
  }
}

void KernelGrid::add_scaled(const KernelGrid& other, double factor)
{
  if (other.values_.size() != values_.size()) throw std::invalid_argument("kernel grids of different layouts");
  for (size_t k = 0; k < values_.size(); ++k) values_[k] += factor * other.values_[k];
}

void KernelGrid::clear()
{
  std::fill(values_.begin(), values_.end(), 0.0);
}

}  // namespace cdpost
