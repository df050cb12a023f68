// The exact 2D Coulomb–Signorini local solver: one contact, all other impulses frozen.
#pragma once

#include <algorithm>
#include <cmath>

namespace cd {

// Normal and tangential components of a local vector (a relative velocity or an impulse).
struct Local2 {
  double n = 0.0;
  double t = 0.0;
};

// Local Delassus operator W = H M^-1 H^T of one contact: symmetric positive definite 2x2,
// mapping a local impulse (N s) to the relative velocity it produces (m/s).
struct Delassus2 {
  double nn = 0.0;
  double nt = 0.0;
  double tt = 0.0;

  Local2 times(Local2 p) const { return {nn * p.n + nt * p.t, nt * p.n + tt * p.t}; }
  Local2 times_normal(double p_n) const { return {nn * p_n, nt * p_n}; }  // W (p_n, 0)
};

// W of a disk contact. The normal passes through both centres (or, on a wall, through the
// disk's centre), so W_nt = 0 and the local problem separates: Signorini on the normal
// impulse, then the tangential impulse clamped to the cone. The inverses are kept so that
// the sweep divides nothing.
struct DiskDelassus {
  double nn = 0.0;  // m/s per N s
  double tt = 0.0;
  double inverse_nn = 0.0;  // N s per m/s
  double inverse_tt = 0.0;

  static DiskDelassus of(double nn, double tt) { return {nn, tt, 1.0 / nn, 1.0 / tt}; }
  Local2 times(Local2 p) const { return {nn * p.n, tt * p.t}; }
  Delassus2 full() const { return {nn, 0.0, tt}; }
};

// Which branch of the Coulomb graph the local solution lies on.
// slip_positive: u_t > 0 and p_t = -mu p_n; slip_negative: u_t < 0 and p_t = +mu p_n.
enum class ContactStatus : unsigned char { no_contact, stick, slip_positive, slip_negative };

struct LocalSolution {
  Local2 impulse;
  ContactStatus status;
};

namespace detail {

// Sliding branch with p_t = -direction * mu * p_n, direction = sign(u_t) in {+1, -1}.
// Valid when the normal impulse is compressive and the sliding velocity has that sign.
inline bool try_slip(const Delassus2& w, Local2 u_free, double mu, double direction, Local2& impulse)
{
  const double normal_stiffness = w.nn - direction * mu * w.nt;
  if (normal_stiffness <= 0.0) return false;
  const double p_n = -u_free.n / normal_stiffness;
  const double u_t = u_free.t + (w.nt - direction * mu * w.tt) * p_n;
  if (p_n < 0.0 || direction * u_t < 0.0) return false;
  impulse = {p_n, -direction * mu * p_n};
  return true;
}

}  // namespace detail

// Solves u = W p + u_free with 0 <= u_n ⊥ p_n >= 0, |p_t| <= mu p_n, and p_t = -mu p_n sign(u_t)
// when u_t != 0, by enumerating the four branches. u_free.n already carries any restitution
// bias. Exact (no iteration, no regularisation); for disks W.nt = 0 and the first valid
// branch is found with one division per component.
inline LocalSolution solve_coulomb_local(const Delassus2& w, Local2 u_free, double mu)
{
  if (u_free.n >= 0.0) return {{0.0, 0.0}, ContactStatus::no_contact};

  const double inv_det = 1.0 / (w.nn * w.tt - w.nt * w.nt);
  const Local2 stick{(-u_free.n * w.tt + u_free.t * w.nt) * inv_det, (-u_free.t * w.nn + u_free.n * w.nt) * inv_det};
  if (stick.n >= 0.0 && std::abs(stick.t) <= mu * stick.n) return {stick, ContactStatus::stick};

  // The sticking impulse leaves the cone on the side of its tangential sign: friction then
  // saturates on that side, i.e. the contact slides the opposite way.
  const double likely = stick.t > 0.0 ? -1.0 : 1.0;
  Local2 impulse;
  if (detail::try_slip(w, u_free, mu, likely, impulse))
    return {impulse, likely > 0.0 ? ContactStatus::slip_positive : ContactStatus::slip_negative};
  if (detail::try_slip(w, u_free, mu, -likely, impulse))
    return {impulse, likely > 0.0 ? ContactStatus::slip_negative : ContactStatus::slip_positive};

  // Unreachable for symmetric positive definite W (a 2D Coulomb problem always has a
  // solution); keep the sliding normal impulse rather than inventing a state.
  const double p_n = std::max(0.0, -u_free.n / w.nn);
  return {{p_n, -likely * mu * p_n}, likely > 0.0 ? ContactStatus::slip_positive : ContactStatus::slip_negative};
}

// The frictionless (mu = 0) local solution: the cone is the half-line p_t = 0, so Signorini
// alone decides, p_n = max(0, -u_free.n / W_nn) for any W. It is what solve_coulomb_local
// returns for mu = 0 (its sliding branch, with normal stiffness W_nn) without trying the
// stick and slip branches first.
inline double solve_frictionless_local(const Delassus2& w, double free_normal_velocity)
{
  return free_normal_velocity >= 0.0 ? 0.0 : -free_normal_velocity / w.nn;
}

// solve_coulomb_local for W = diag(nn, tt), given the impulse that would stop the contact
// outright, stick = -W^-1 u_free. With no coupling the slip branches keep the sticking
// normal impulse, so the solution is that impulse with p_n >= 0 and p_t clamped to the cone:
// the same branches as the general solver, with no division. NaN propagates (std::max keeps it).
inline Local2 solve_coulomb_disk(Local2 stick, double mu)
{
  const double p_n = std::max(stick.n, 0.0);
  const double bound = mu * p_n;
  return {p_n, std::min(std::max(stick.t, -bound), bound)};
}

// Projection of an impulse onto the friction cone {|p_t| <= mu p_n}.
Local2 project_on_friction_cone(Local2 p, double mu);

// Squared natural-map residual |p - proj_K(p - u_hat)|^2 with De Saxce's modified velocity
// u_hat = (u_n + mu |u_t|, u_t): zero exactly when (p, u) satisfies the Coulomb–Signorini law.
double natural_map_residual_squared(Local2 impulse, Local2 velocity, double mu);

}  // namespace cd
