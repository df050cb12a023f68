// The numbers a source study states (results/source.csv: Staron's 2D Contact Dynamics study of
// flows on erodible beds), each with the interval that counts as agreeing, and its flow rules
// evaluated at given angles or inertial numbers, I = d U / (sqrt(g) h^1.5).
//
// The file: '#' lines (its provenance), then the header
// name,source_low,source_high,accepted_low,accepted_high,unit,description and one row per
// number; source_low = source_high for a single value; accepted_* both empty for a number shown
// but not compared. Signs are +1 (rises), -1 (falls), 0 (no dependence).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace cdpost {

struct SourceValue {
  double low = 0, high = 0;  // the source's value (low = high) or range
  std::optional<double> accepted_low, accepted_high;
  std::string unit, description;
  bool compared() const { return accepted_low.has_value(); }
  bool accepts(double x) const { return compared() && x >= *accepted_low && x <= *accepted_high; }
};

struct SourceNumbers {
  std::string path;
  std::map<std::string, SourceValue> values;
  std::vector<double> frictions;  // those with a Pouliquen row, ascending

  bool has(const std::string& name) const { return values.count(name) > 0; }
  // The row `name`, or an InputError naming the file and the missing row.
  const SourceValue& at(const std::string& name) const;
  double value(const std::string& name) const { return at(name).low; }
  // The rule's angles (deg) and l at friction mu: {theta1, theta2, l or I0}.
  struct Rule {
    double tan1, tan2, scale;
  };
  Rule pouliquen(double mu) const;
  Rule mu_of_i(double mu) const;
};

// Reads and checks the file (every row: low <= high, both accepted bounds or none, low <= high).
SourceNumbers read_source(const std::string& path);

// "_mu<mu>" as the series' fit names write it.
std::string friction_suffix(double mu);

// The source's Pouliquen rule, tan theta = tan1 + (tan2 - tan1) exp(-beta/(l I)): theta (deg)
// at I, and I at theta (none outside theta1 < theta < theta2).
double pouliquen_angle(const SourceNumbers& source, double mu, double inertial);
std::optional<double> pouliquen_inertial(const SourceNumbers& source, double mu, double theta_deg);
// The source's mu(I) rule, tan theta = tan1 + (tan2 - tan1)/(I0/I + 1): theta at I, I at theta.
double mu_of_i_angle(const SourceNumbers& source, double mu, double inertial);
std::optional<double> mu_of_i_inertial(const SourceNumbers& source, double mu, double theta_deg);

// The inertial numbers a run's I can be read as (fit/inertial_number.h), each a result of the run.
struct InertialDefinition {
  std::string result;  // I (the source's stated one), I_bagnold, I_local
  std::string name;    // in tables and figures
};
extern const std::vector<InertialDefinition> kInertialDefinitions;

// The source's two flow rules at one of its angles: the inertial number each gives.
struct InertialCheck {
  double mu = 0, theta_deg = 0;
  double pouliquen = 0, mu_of_i = 0;  // I
  // 2.5/sqrt(phi cos theta), GDR MiDi's I over the stated one in a Bagnold layer, with phi from
  // the source's phi(U) law at the Pouliquen rule's U = I h^1.5, h the middle of its range of h.
  double bagnold_factor = 0;
};
// At every whole degree of each friction's angles_mu<mu> range.
std::vector<InertialCheck> source_inertial_numbers(const SourceNumbers& source);
// The Pouliquen rule's I of `check` read as the definition whose result is `result` (I or
// I_bagnold); none for one the source's numbers cannot give (I_local needs profiles).
std::optional<double> pouliquen_inertial_as(const InertialCheck& check, const std::string& result);
// The I0 with which the mu(I) rule gives the Pouliquen rule's I (read as `result`) in the geometric
// mean over `checks`: its I is proportional to I0, so I0 times the geometric mean of pouliquen/mu_of_i.
double reconciling_i0(const SourceNumbers& source, const std::vector<InertialCheck>& checks,
                      const std::string& result = "I");
// Whether the two rules give the same I within a factor `tolerance` at every angle checked, the
// Pouliquen rule's I read as `result`; none when the source's numbers cannot give it so.
std::optional<bool> rules_consistent(const std::vector<InertialCheck>& checks, const std::string& result = "I",
                                     double tolerance = 1.5);

}  // namespace cdpost
