// The parameters a run folder records in chute.params (io/chute_record.h) and the command line
// may give instead: d, g, the height z0 of the wall tops, the sample rate and the cell length. A value given on
// the command line wins, then the record's, then the default.
#pragma once

#include <optional>
#include <string>

#include "analysis/run_analysis.h"
#include "io/chute_record.h"
#include "io/options.h"

namespace cdpost {

// Whether a command must know the wall tops: `run` and `series` measure z from them; `spectrum`
// does not use them and `snapshot` draws no walls without them.
enum class WallTops { required, optional };

struct RunParameters {
  Units units;
  bool d_given = false;                  // d from --d or the record, not the default
  std::optional<double> z0;              // wall-top height, input length units
  std::optional<double> sample_rate_hz;  // of the uniform samples; none: the time file's longest interval
  std::optional<double> cell_length_d;   // L in d: the columns of columns.chunk tile it
  bool recorded = false;                 // the folder holds a chute.params
  std::string description;               // one line: which values are used, and where from
};

// d, g and the input units from --d, --g, --units, --length-unit and --time-unit; d and g not
// given are the record's (if any), else the defaults. UsageError for a bad value.
Units units_from(const ParsedOptions& options, const std::string& command, const ChuteRecord* record = nullptr);

// The parameters for the run folder `directory`. InputError when the wall tops are required and
// neither --z0 nor the folder's record gives them.
RunParameters run_parameters(const ParsedOptions& options, const std::string& command, const std::string& directory,
                             WallTops wall_tops);

// settings.units, z0, sample_rate_hz, cell_length_d and parameters from run_parameters(..., settings.directory, required).
void apply_run_parameters(RunSettings& settings, const ParsedOptions& options, const std::string& command);

}  // namespace cdpost
