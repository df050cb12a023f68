// The cdpost command line: subcommands run, series, spectrum, snapshot.
#pragma once

#include <string>
#include <vector>

namespace cdpost {

// Runs the command line (without the program name) and returns the exit status: 0 on
// success, 1 for a problem with the data or the analysis, 2 for a wrong command line.
// Errors are printed on stderr as one line.
int run_command_line(const std::vector<std::string>& arguments);

}  // namespace cdpost
