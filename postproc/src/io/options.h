// Command-line options: "--name value" pairs, "--flag" switches and positional arguments,
// checked against a table that also produces the --help text.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace cdpost {

// A wrong command line; main() prints it with a pointer to --help.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct OptionSpec {
  std::string name;        // without the leading "--"
  std::string value_name;  // empty for a switch
  std::string help;
};

class ParsedOptions {
 public:
  std::vector<std::string> positional;
  bool flag(const std::string& name) const { return flags_.count(name) > 0; }
  std::optional<std::string> text(const std::string& name) const;
  std::optional<double> number(const std::string& name) const;  // UsageError if not a finite number
  std::optional<long> integer(const std::string& name) const;

 private:
  friend ParsedOptions parse_options(const std::string&, const std::vector<std::string>&,
                                     const std::vector<OptionSpec>&);
  std::string command_;
  std::map<std::string, std::string> values_;
  std::set<std::string> flags_;
};

ParsedOptions parse_options(const std::string& command, const std::vector<std::string>& arguments,
                            const std::vector<OptionSpec>& specs);
std::string options_help(const std::vector<OptionSpec>& specs);

}  // namespace cdpost
