// Saved steps of the core (fix contact/dynamics save_problems, .cdp) as FCLIB local problems:
//
//   cdp_to_fclib --out DIR PROBLEM.cdp ...
//
// writes DIR/<name>.hdf5 for each PROBLEM (bench/peers/local_problem.h: W, q, mu, the warm
// start in the guess slot, the impulse scale in the description), reads it back and refuses
// it unless it is the same problem bit for bit.
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "local_problem.h"

namespace {

std::string stem(const std::string& path)
{
  const std::string name = path.substr(path.find_last_of('/') + 1);
  return name.substr(0, name.rfind(".cdp"));
}

bool same(const peers::LocalProblem& a, const peers::LocalProblem& b)
{
  return a.contacts == b.contacts && a.column_start == b.column_start && a.row == b.row && a.value == b.value &&
         a.q == b.q && a.mu == b.mu && a.warm_start == b.warm_start && a.impulse_scale == b.impulse_scale &&
         a.label == b.label;
}

}  // namespace

int main(int argc, char** argv)
{
  try {
    std::string out;
    std::vector<std::string> problems;
    for (int i = 1; i < argc; i++) {
      const std::string arg = argv[i];
      if (arg == "--out" && i + 1 < argc) out = argv[++i];
      else if (arg.rfind("--", 0) == 0) throw std::invalid_argument("cdp_to_fclib: unknown option " + arg);
      else problems.push_back(arg);
    }
    if (out.empty() || problems.empty()) throw std::invalid_argument("usage: cdp_to_fclib --out DIR PROBLEM.cdp ...");
    for (const std::string& path : problems) {
      const peers::LocalProblem local = peers::local_problem(cd::read_problem(path));
      const std::string written = out + "/" + stem(path) + ".hdf5";
      peers::write_fclib(written, local);
      if (!same(local, peers::read_fclib(written)))
        throw std::runtime_error("cdp_to_fclib: " + written + " does not read back as the problem written");
      std::cout << written << ": " << local.contacts << " contacts\n";
    }
    return 0;
  } catch (const std::exception& failure) {
    std::cerr << failure.what() << "\n";
    return 1;
  }
}
