// What cdref reads of a run folder besides cdpost's analysis of it: the samples' times, the cost
// of the flow stage from the logs (and run_comparison.sh's timing.txt), the overlaps in the dump.
#pragma once

#include <string>
#include <vector>

#include "comparison.h"

namespace cdref {

// Time (input units) and TimeStep of every sample of flow.time.
struct Samples {
  std::vector<double> time, timestep, u_flow;
};

Samples read_samples(const cdpost::RunSettings& s);

// The run's own flow stage (the last loop of its log) plus those of the continuation runs
// in its part2, part3, ... subdirectories (in.chute_rigid in parts).
void read_cost(ComparedRun& run, const Samples& samples, double time_unit_s, std::vector<std::string>& warnings);

// The overlaps of the dump frames inside the run's analysis window (a warning when there is no dump).
void read_overlaps(ComparedRun& run, const CompareSettings& settings, const cdpost::RunSettings& s,
                   const Samples& samples, std::vector<std::string>& warnings);

}  // namespace cdref
