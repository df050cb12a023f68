// A command-line option's number for the peer tools (peer_bench, peer_limits): all of the text a
// number of the type, else refused in one line naming the tool and the option.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace peers {

template <class Number>
Number option_number(const std::string& tool, const std::string& option, const std::string& text)
{
  std::size_t used = 0;
  Number value{};
  try {
    if constexpr (std::is_integral_v<Number>) value = static_cast<Number>(std::stoi(text, &used));
    else value = static_cast<Number>(std::stod(text, &used));
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size())
    throw std::invalid_argument(tool + ": " + option + " needs a number, got '" + text + "'");
  return value;
}

}  // namespace peers
