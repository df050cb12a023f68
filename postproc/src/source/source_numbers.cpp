#include "source/source_numbers.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "fit/inertial_number.h"
#include "io/ave_time.h"
#include "io/line_source.h"
#include "io/tokens.h"
#include "signal/statistics.h"

namespace cdpost {

namespace {

const std::vector<std::string> kHeader{"name",          "source_low", "source_high", "accepted_low",
                                       "accepted_high", "unit",       "description"};

// A friction's rows are named by it: pouliquen_theta1_mu0.5, ...
const std::string kFrictionStem = "pouliquen_theta1_mu";

std::vector<std::string> fields_of(const std::string& line)
{
  std::vector<std::string> fields;
  std::stringstream stream(line);
  std::string field;
  while (std::getline(stream, field, ',')) fields.push_back(field);
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

std::optional<double> optional_number(const std::string& token, const LineSource& source, const std::string& what)
{
  if (token.empty()) return std::nullopt;
  return parse_number(token, source, what);
}

SourceValue parse_row(const std::vector<std::string>& f, const LineSource& source)
{
  SourceValue v;
  v.low = parse_number(f[1], source, f[0] + " source_low");
  v.high = parse_number(f[2], source, f[0] + " source_high");
  v.accepted_low = optional_number(f[3], source, f[0] + " accepted_low");
  v.accepted_high = optional_number(f[4], source, f[0] + " accepted_high");
  v.unit = f[5];
  v.description = f[6];
  if (v.low > v.high) source.fail(f[0] + ": source_low is above source_high");
  if (v.accepted_low.has_value() != v.accepted_high.has_value())
    source.fail(f[0] + ": give both accepted bounds or neither");
  if (v.accepted_low && *v.accepted_low > *v.accepted_high) source.fail(f[0] + ": accepted_low is above accepted_high");
  return v;
}

double tan_deg(double deg)
{
  return std::tan(deg * M_PI / 180);
}

double deg_atan(double t)
{
  return std::atan(t) * 180 / M_PI;
}

}  // namespace

std::string friction_suffix(double mu)
{
  return "_mu" + format_estimate(mu, std::nullopt);
}

const SourceValue& SourceNumbers::at(const std::string& name) const
{
  auto found = values.find(name);
  if (found == values.end()) throw InputError(path, 0, "no row '" + name + "'");
  return found->second;
}

SourceNumbers::Rule SourceNumbers::pouliquen(double mu) const
{
  const auto s = friction_suffix(mu);
  return {tan_deg(value("pouliquen_theta1" + s)), tan_deg(value("pouliquen_theta2" + s)), value("pouliquen_ell" + s)};
}

SourceNumbers::Rule SourceNumbers::mu_of_i(double mu) const
{
  const auto s = friction_suffix(mu);
  return {tan_deg(value("muI_theta1" + s)), tan_deg(value("muI_theta2" + s)), value("muI_I0")};
}

SourceNumbers read_source(const std::string& path)
{
  SourceNumbers source;
  source.path = path;
  LineSource lines(path);
  std::string line;
  bool have_header = false;
  while (lines.next(line)) {
    if (is_blank(line) || is_comment(line)) continue;
    const auto fields = fields_of(line);
    if (!have_header) {
      if (fields != kHeader) lines.fail("expected the header " + join_names(kHeader));
      have_header = true;
      continue;
    }
    if (fields.size() != kHeader.size())
      lines.fail("expected " + std::to_string(kHeader.size()) + " fields, found " + std::to_string(fields.size()) +
                 " (a description holds no comma)");
    if (!source.values.emplace(fields[0], parse_row(fields, lines)).second)
      lines.fail("'" + fields[0] + "' is given twice");
    if (fields[0].rfind(kFrictionStem, 0) == 0)
      source.frictions.push_back(parse_number(fields[0].substr(kFrictionStem.size()), lines, "friction"));
  }
  if (!have_header) throw InputError(path, 0, "file is empty");
  std::sort(source.frictions.begin(), source.frictions.end());
  for (double mu : source.frictions) source.pouliquen(mu), source.mu_of_i(mu);  // every rule complete
  source.at("pouliquen_beta");
  return source;
}

double pouliquen_angle(const SourceNumbers& source, double mu, double inertial)
{
  const auto r = source.pouliquen(mu);
  return deg_atan(r.tan1 + (r.tan2 - r.tan1) * std::exp(-source.value("pouliquen_beta") / (r.scale * inertial)));
}

std::optional<double> pouliquen_inertial(const SourceNumbers& source, double mu, double theta_deg)
{
  const auto r = source.pouliquen(mu);
  const double t = tan_deg(theta_deg);
  if (!(t > r.tan1 && t < r.tan2)) return std::nullopt;
  return source.value("pouliquen_beta") / (r.scale * std::log((r.tan2 - r.tan1) / (t - r.tan1)));
}

double mu_of_i_angle(const SourceNumbers& source, double mu, double inertial)
{
  const auto r = source.mu_of_i(mu);
  return deg_atan(r.tan1 + (r.tan2 - r.tan1) / (r.scale / inertial + 1));
}

std::optional<double> mu_of_i_inertial(const SourceNumbers& source, double mu, double theta_deg)
{
  const auto r = source.mu_of_i(mu);
  const double t = tan_deg(theta_deg);
  if (!(t > r.tan1 && t < r.tan2)) return std::nullopt;
  return r.scale * (t - r.tan1) / (r.tan2 - t);
}

const std::vector<InertialDefinition> kInertialDefinitions{
    {"I", "the stated I = d U/(sqrt(g) h^1.5)"},
    {"I_bagnold", "GDR MiDi's I, Bagnold shear rate 5U/(2h), basal pressure"},
    {"I_local", "GDR MiDi's I at mid-layer, measured du/dz and weight above"}};

std::vector<InertialCheck> source_inertial_numbers(const SourceNumbers& source)
{
  std::vector<InertialCheck> checks;
  const auto& thickness = source.at("h");
  const double h = 0.5 * (thickness.low + thickness.high);
  for (double mu : source.frictions) {
    const auto& angles = source.at("angles" + friction_suffix(mu));
    const double phi_c = source.value("phi_c" + friction_suffix(mu)), k = source.value("phi_k");
    for (double theta = std::ceil(angles.low); theta <= angles.high; theta += 1) {
      auto p = pouliquen_inertial(source, mu, theta), m = mu_of_i_inertial(source, mu, theta);
      if (!p || !m) continue;
      const double velocity = *p * std::pow(h, 1.5);
      checks.push_back({mu, theta, *p, *m, bagnold_inertial_number(velocity, h, phi_c - k * velocity, theta) / *p});
    }
  }
  return checks;
}

std::optional<double> pouliquen_inertial_as(const InertialCheck& check, const std::string& result)
{
  if (result == "I") return check.pouliquen;
  if (result == "I_bagnold") return check.pouliquen * check.bagnold_factor;
  return std::nullopt;
}

double reconciling_i0(const SourceNumbers& source, const std::vector<InertialCheck>& checks, const std::string& result)
{
  double log_sum = 0;
  for (const auto& c : checks) log_sum += std::log(pouliquen_inertial_as(c, result).value_or(NAN) / c.mu_of_i);
  return source.value("muI_I0") * std::exp(log_sum / static_cast<double>(checks.size()));
}

std::optional<bool> rules_consistent(const std::vector<InertialCheck>& checks, const std::string& result,
                                     double tolerance)
{
  for (const auto& c : checks) {
    const auto pouliquen = pouliquen_inertial_as(c, result);
    if (!pouliquen) return std::nullopt;
    if (*pouliquen > tolerance * c.mu_of_i || c.mu_of_i > tolerance * *pouliquen) return false;
  }
  return true;
}

}  // namespace cdpost
