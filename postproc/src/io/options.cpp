#include "io/options.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>

namespace cdpost {

std::optional<std::string> ParsedOptions::text(const std::string& name) const
{
  auto found = values_.find(name);
  if (found == values_.end()) return std::nullopt;
  return found->second;
}

std::optional<double> ParsedOptions::number(const std::string& name) const
{
  auto value = text(name);
  if (!value) return std::nullopt;
  double parsed = 0;
  auto [end, error] = std::from_chars(value->data(), value->data() + value->size(), parsed);
  if (error != std::errc() || end != value->data() + value->size() || !std::isfinite(parsed))
    throw UsageError(command_ + ": --" + name + ": '" + *value + "' is not a number");
  return parsed;
}

std::optional<long> ParsedOptions::integer(const std::string& name) const
{
  auto value = text(name);
  if (!value) return std::nullopt;
  long parsed = 0;
  auto [end, error] = std::from_chars(value->data(), value->data() + value->size(), parsed);
  if (error != std::errc() || end != value->data() + value->size())
    throw UsageError(command_ + ": --" + name + ": '" + *value + "' is not an integer");
  return parsed;
}

ParsedOptions parse_options(const std::string& command, const std::vector<std::string>& arguments,
                            const std::vector<OptionSpec>& specs)
{
  ParsedOptions parsed;
  parsed.command_ = command;
  for (size_t i = 0; i < arguments.size(); ++i) {
    const std::string& argument = arguments[i];
    if (argument.rfind("--", 0) != 0) {
      parsed.positional.push_back(argument);
      continue;
    }
    std::string name = argument.substr(2);
    auto spec = std::find_if(specs.begin(), specs.end(), [&](const OptionSpec& s) { return s.name == name; });
    if (spec == specs.end()) throw UsageError(command + ": unknown option '" + argument + "'");
    if (spec->value_name.empty()) {
      parsed.flags_.insert(name);
      continue;
    }
    if (i + 1 >= arguments.size())
      throw UsageError(command + ": option '" + argument + "' needs a value (" + spec->value_name + ")");
    parsed.values_[name] = arguments[++i];
  }
  return parsed;
}

std::string options_help(const std::vector<OptionSpec>& specs)
{
  std::ostringstream out;
  for (const auto& spec : specs) {
    std::string left = "  --" + spec.name + (spec.value_name.empty() ? "" : " " + spec.value_name);
    out << left << std::string(left.size() < 30 ? 30 - left.size() : 1, ' ') << spec.help << '\n';
  }
  return out.str();
}

}  // namespace cdpost
