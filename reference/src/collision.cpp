#include "collision.h"

#include <cmath>

#include "io/line_source.h"
#include "io/tokens.h"

namespace cdref {

CollisionResult analyse_collision(const std::string& path)
{
  cdpost::LineSource source(path);
  std::string line;
  CollisionResult result;
  bool have_speed = false, touched = false, separated = false;
  while (source.next(line)) {
    if (cdpost::is_blank(line) || cdpost::is_comment(line)) continue;
    auto tokens = cdpost::split_whitespace(line);
    if (tokens.size() != 3)
      source.fail("expected 'step gap velocity', found " + std::to_string(tokens.size()) + " values");
    cdpost::parse_integer(tokens[0], source, "step");
    const double gap = cdpost::parse_number(tokens[1], source, "gap");
    const double velocity = cdpost::parse_number(tokens[2], source, "velocity");
    if (!have_speed) {
      if (velocity >= 0)
        source.fail("the bodies do not approach at the start (velocity " + std::string(tokens[2]) + ")");
      result.approach_speed = -velocity;
      have_speed = true;
    }
    if (gap < 0) {
      if (separated) source.fail("a second contact after the bodies separated");
      touched = true;
      ++result.contact_steps;
    } else if (touched && !separated) {
      separated = true;
      result.restitution = velocity / result.approach_speed;
    }
  }
  if (!touched) throw cdpost::InputError(path, 0, "the bodies never touch");
  if (!separated) throw cdpost::InputError(path, 0, "the bodies are still in contact at the end");
  return result;
}

}  // namespace cdref
