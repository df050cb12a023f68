// chute.params: the record inputs/in.chute writes into its folder as a chute stage starts: the
// wall tops that z is measured from, the sample rate of the outputs, d, g and the scene's
// parameters; one "name value" a line in SI units, '#' lines are comments.
#pragma once

#include <map>
#include <optional>
#include <string>

namespace cdpost {

constexpr const char* kChuteRecordFile = "chute.params";

struct ChuteRecord {
  std::string source;                    // the file read
  std::map<std::string, double> values;  // y_top_m, sample_rate_hz, d_m, g_mps2, theta_deg, ...
  std::optional<double> find(const std::string& name) const;
};

// DIRECTORY/chute.params, or nothing when the folder holds none. A line that is not one name
// and one finite number, or a name given twice, is an InputError naming the file and line.
std::optional<ChuteRecord> read_chute_record(const std::string& directory);

}  // namespace cdpost
