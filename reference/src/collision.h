// A binary collision recorded by the collision decks (in.collision_granular,
// in.collision_liggghts): the restitution coefficient and the contact duration in steps,
// which check the damping and the time-step rule of the chute decks in each code.
#pragma once

#include <string>

namespace cdref {

struct CollisionResult {
  double restitution = 0;     // -(normal relative velocity after) / (before)
  long contact_steps = 0;     // steps with a negative gap
  double approach_speed = 0;  // |normal relative velocity| before contact
};

// Reads a file of "step gap normal_relative_velocity" rows ('#' comments allowed), the
// velocity negative while the bodies approach. Throws an InputError if the bodies never touch
// or are still touching at the end.
CollisionResult analyse_collision(const std::string& path);

}  // namespace cdref
