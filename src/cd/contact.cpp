#include "cd/contact.h"

#include <algorithm>

namespace cd {

void BodySet::reset(int body_count)
{
  inertia.assign(body_count, BodyInertia{});
  start_velocity.assign(body_count, BodyVelocity{});
  velocity.assign(body_count, BodyVelocity{});
}

Contact contact_frame(const ContactGeometry& g)
{
  Contact c;
  c.body_a = g.body_a;
  c.body_b = g.body_b;
  c.normal_x = g.normal_x;
  c.normal_y = g.normal_y;
  c.lever_a = g.lever_a;
  c.lever_b = g.lever_b;
  // Until prepare_mechanics adds the normal law's part, the bias is the image's velocity only.
  c.velocity_bias = {-(g.image_vx * g.normal_x + g.image_vy * g.normal_y),
                     -(-g.image_vx * g.normal_y + g.image_vy * g.normal_x)};
  return c;
}

bool is_candidate(const Contact& frame, double gap, const BodySet& bodies, const StepParameters& step, double alert)
{
  const Local2 u_free = law_velocity(frame, bodies.velocity[frame.body_a], bodies.velocity[frame.body_b]);
  return gap + step.advance() * std::min(u_free.n, 0.0) <= alert;
}

void prepare_mechanics(Contact& c, double gap, const ContactLaw& law, const BodySet& bodies, const StepParameters& step)
{
  const BodyInertia& a = bodies.inertia[c.body_a];
  const BodyInertia& b = bodies.inertia[c.body_b];
  c.inv_mass_a = a.inv_mass;
  c.inv_mass_b = b.inv_mass;
  c.spin_gain_a = c.lever_a * a.inv_inertia;
  c.spin_gain_b = c.lever_b * b.inv_inertia;
  const double translation = a.inv_mass + b.inv_mass;
  // For disks the normal passes through both centres: no normal-tangential coupling.
  c.delassus = DiskDelassus::of(translation, translation + c.lever_a * c.spin_gain_a + c.lever_b * c.spin_gain_b);
  c.mu = law.mu;
  c.impulse = {};

  // A touching pair is an impact whatever its pre-step velocity, and at e = 0 the normal law adds
  // nothing: nothing to read, so a scene without restitution does not pay for it.
  if (gap <= 0.0 && law.restitution == 0.0) return;
  // The frame's bias is the image's velocity (contact_frame), part of the pre-step velocity.
  const double u_start = law_velocity(c, bodies.start_velocity[c.body_a], bodies.start_velocity[c.body_b]).n;
  const double advance = step.advance();
  const bool impact = gap <= 0.0 || gap + advance * u_start <= 0.0;
  c.velocity_bias.n += impact ? law.restitution * std::min(u_start, 0.0) : gap / advance;
}

Contact prepared_contact(const ContactGeometry& geometry, const ContactLaw& law, const BodySet& bodies,
                         const StepParameters& step)
{
  Contact c = contact_frame(geometry);
  prepare_mechanics(c, geometry.gap, law, bodies, step);
  return c;
}

void warm_start(Contact& c, Local2 carried)
{
  c.impulse = {carried.n, c.mu == 0.0 ? 0.0 : carried.t};
}

void apply_impulses(const std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity)
{
  for (const Contact& c : contacts) apply_impulse(c, c.impulse, velocity[c.body_a], velocity[c.body_b]);
}

}  // namespace cd
