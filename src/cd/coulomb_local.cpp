#include "cd/coulomb_local.h"

#include <cmath>

namespace cd {
Local2 project_on_friction_cone(Local2 p, double mu)
{
  const double t_abs = std::abs(p.t);
  if (t_abs <= mu * p.n) return p;
  if (mu * t_abs <= -p.n) return {0.0, 0.0};
  const double n = (p.n + mu * t_abs) / (1.0 + mu * mu);
  return {n, std::copysign(mu * n, p.t)};
}

double natural_map_residual_squared(Local2 impulse, Local2 velocity, double mu)
{
  const Local2 modified{velocity.n + mu * std::abs(velocity.t), velocity.t};
  const Local2 projected = project_on_friction_cone({impulse.n - modified.n, impulse.t - modified.t}, mu);
  const double dn = impulse.n - projected.n;
  const double dt = impulse.t - projected.t;
  return dn * dn + dt * dt;
}

}  // namespace cd
