#include "source/source_comparison.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "signal/statistics.h"

namespace cdpost {

std::string verdict_text(const SourceRow& row)
{
  const bool sign = row.kind == RowKind::Sign;
  switch (row.verdict) {
    case Verdict::Agrees: return sign ? "sign agrees" : "agrees";
    case Verdict::Outside: return sign ? "sign differs" : "outside";
    case Verdict::NotATarget: return "not a target";
    case Verdict::ByConstruction: return "set by construction";
    case Verdict::Shown: break;
  }
  return "shown";
}

std::vector<SourceRow> grouped(std::vector<SourceRow> rows)
{
  auto group = [](const SourceRow& row) {
    if (row.kind == RowKind::Sign) return 1;
    return row.verdict == Verdict::ByConstruction || row.key.rfind("angles", 0) == 0 ? 2 : 0;
  };
  std::stable_sort(rows.begin(), rows.end(),
                   [&](const SourceRow& a, const SourceRow& b) { return group(a) < group(b); });
  return rows;
}

namespace {

// Three significant digits (four for a packing fraction): enough to read a comparison.
std::string number(double value, int digits = 3)
{
  char text[32];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return text;
}

std::string mu_text(double mu)
{
  return "mu " + number(mu);
}

std::string range_text(double low, double high)
{
  return low == high ? number(low) : number(low) + " to " + number(high);
}

std::string source_text(const SourceValue& v)
{
  return range_text(v.low, v.high) + (v.unit.empty() ? "" : " " + v.unit);
}

std::string accepted_text(const SourceValue& v)
{
  return v.compared() ? range_text(*v.accepted_low, *v.accepted_high) + (v.unit.empty() ? "" : " " + v.unit) : "–";
}

Verdict verdict_of(bool agrees)
{
  return agrees ? Verdict::Agrees : Verdict::Outside;
}

// The smallest and largest of `values`, as text, and whether all lie in `v`'s accepted interval.
struct Spread {
  double low = INFINITY, high = -INFINITY;
  void add(double x) { low = std::min(low, x), high = std::max(high, x); }
  bool empty() const { return low > high; }
  bool within(const SourceValue& v) const { return v.accepts(low) && v.accepts(high); }
  std::string text(int digits = 3) const { return number(low, digits) + " to " + number(high, digits); }
};

// +1 rises, -1 falls, 0 neither beyond two standard errors.
int sign_of(const Estimate& e)
{
  const double margin = 2 * e.error.value_or(0);
  return e.value - margin > 0 ? 1 : e.value + margin < 0 ? -1 : 0;
}

// +1 or -1 for a correlation with a two-sided p-value below 0.05, else 0.
int sign_of(const CorrelationTest& t)
{
  return t.p_value < 0.05 ? (t.r > 0 ? 1 : -1) : 0;
}

std::string sign_text(int sign)
{
  return sign > 0 ? "rises" : sign < 0 ? "falls" : "no dependence";
}

std::string correlation_text(const CorrelationTest& t)
{
  char text[96];
  std::snprintf(text, sizeof text, "r = %.2f, p = %.1g, %d runs", t.r, t.p_value, t.n);
  return text;
}

struct Comparer {
  const SeriesAnalysis& series;
  const SourceNumbers& source;
  std::vector<SourceRow> rows;

  std::set<double> frictions() const
  {
    std::set<double> mus;
    for (const auto& run : series.runs) mus.insert(run.entry.mu);
    return mus;
  }
  bool source_has(double mu) const
  {
    return std::find(source.frictions.begin(), source.frictions.end(), mu) != source.frictions.end();
  }
  const ResultRow* fit(const std::string& name) const { return series.fits.find(name); }

  // Each run at friction mu against the source's rule at the run's own I (read as `definition`):
  // the angle offset, compared with the tolerance unless `fixed` gives the verdict.
  void rule_as_curve(double mu, const std::string& key, const std::string& rule,
                     double (*angle)(const SourceNumbers&, double, double), const InertialDefinition& definition,
                     std::optional<Verdict> fixed)
  {
    Spread offset, ratio;
    const bool stated = definition.result == "I";
    for (const auto& run : series.runs) {
      const auto inertial = run.estimate(definition.result);
      if (run.entry.mu != mu || !inertial) continue;
      offset.add(run.entry.theta_deg - angle(source, mu, inertial->value));
      if (auto source_i = pouliquen_inertial(source, mu, run.entry.theta_deg);
          source_i && key == "pouliquen_curve_angle" && stated)
        ratio.add(inertial->value / *source_i);  // = U / U_source(theta, h) at the run's h
    }
    if (offset.empty()) return;
    const auto& v = source.at(key);
    std::string ours = "theta - theta_source(I): " + offset.text() + " deg";
    if (!ratio.empty()) ours += "; U/U_source(theta, h): " + ratio.text();
    rows.push_back({key + (stated ? "" : "_" + definition.result) + friction_suffix(mu),
                    rule + " as a curve, " + mu_text(mu) + (stated ? "" : ", I read as " + definition.name), "0 deg",
                    accepted_text(v) + " at every run", ours, fixed.value_or(verdict_of(offset.within(v)))});
  }

  // Pouliquen's rule is stated in U and h, so its curve is compared under the stated I only; the
  // mu(I) rule under each I with which the source's own two rules give the same I (its fit cannot
  // have used another), not a target under one with which they disagree, and shown under one the
  // source's numbers cannot test (the local I).
  void flow_rules()
  {
    const auto checks = source_inertial_numbers(source);
    const std::string pouliquen = "Pouliquen's rule (beta = " + number(source.value("pouliquen_beta")) + ")";
    for (const auto& definition : kInertialDefinitions)
      for (double mu : frictions())
        if (source_has(mu))
          rule_as_curve(mu, "pouliquen_curve_angle", pouliquen, pouliquen_angle, definition,
                        definition.result == "I" ? std::nullopt : std::optional<Verdict>(Verdict::Shown));
    for (const auto& definition : kInertialDefinitions) {
      const auto consistent = rules_consistent(checks, definition.result);
      const auto fixed = !consistent   ? std::optional<Verdict>(Verdict::Shown)
                         : *consistent ? std::nullopt
                                       : std::optional<Verdict>(Verdict::NotATarget);
      for (double mu : frictions())
        if (source_has(mu)) rule_as_curve(mu, "muI_curve_angle", "the mu(I) rule", mu_of_i_angle, definition, fixed);
    }
  }

  void packing()
  {
    std::vector<std::pair<double, double>> phi_c;  // (mu, ours)
    for (double mu : frictions()) {
      const auto* ours = fit("phi_c" + friction_suffix(mu));
      if (!ours) continue;
      phi_c.emplace_back(mu, ours->value);
      if (!source_has(mu)) continue;
      const auto& v = source.at("phi_c" + friction_suffix(mu));
      rows.push_back({"phi_c" + friction_suffix(mu), "phi_c of phi = phi_c - k U, " + mu_text(mu), source_text(v),
                      accepted_text(v), format_estimate(ours->value, ours->error), verdict_of(v.accepts(ours->value))});
    }
    for (double mu : frictions()) {
      const auto* own = fit("phi_c_own_k" + friction_suffix(mu));
      const auto* k = fit("phi_k_own" + friction_suffix(mu));
      const auto* slowest = fit("phi_slowest_U" + friction_suffix(mu));
      if (!own || !k || !source_has(mu)) continue;
      const auto& v = source.at("phi_c" + friction_suffix(mu));
      rows.push_back({"phi_c_own_k" + friction_suffix(mu), "phi_c with its own k, " + mu_text(mu), source_text(v),
                      accepted_text(v),
                      format_estimate(own->value, own->error) + " (k " + format_estimate(k->value, k->error) +
                          ", from U >= " + number(slowest ? slowest->value : NAN) + ")",
                      Verdict::Shown});
    }
    if (const auto* k = fit("phi_k")) {
      const auto& v = source.at("phi_k");
      rows.push_back({"phi_k", "k of phi = phi_c - k U/sqrt(g d)", source_text(v), accepted_text(v),
                      format_estimate(k->value, k->error), verdict_of(v.accepts(k->value))});
    }
    for (double mu : frictions()) {
      if (!source_has(mu)) continue;
      Spread offset;
      const double phi_c_source = source.value("phi_c" + friction_suffix(mu)), k = source.value("phi_k");
      for (const auto& run : series.runs)
        if (auto phi = run.estimate("phi"); run.entry.mu == mu && phi)
          offset.add(phi->value - (phi_c_source - k * run.value("U")));
      if (offset.empty()) continue;
      const auto& v = source.at("phi_law");
      rows.push_back({"phi_law" + friction_suffix(mu), "phi against the source's phi(U) law, " + mu_text(mu), "0",
                      accepted_text(v) + " at every run", "phi - phi_source(U): " + offset.text(2),
                      verdict_of(offset.within(v))});
    }
    if (phi_c.size() > 1) {
      int sign = 0;
      bool monotonic = true;
      for (size_t i = 1; i < phi_c.size(); ++i) {
        const int step = phi_c[i].second > phi_c[i - 1].second ? 1 : phi_c[i].second < phi_c[i - 1].second ? -1 : 0;
        if (i == 1) sign = step;
        else if (step != sign) monotonic = false;
      }
      if (!monotonic) sign = 0;
      std::string ours;
      for (const auto& [mu, value] : phi_c) ours += (ours.empty() ? "" : ", ") + number(value, 4);
      sign_row("sign_phi_c_vs_mu", "phi_c against mu", sign_text(sign) + " (" + ours + ")", sign);
    }
  }

  void sign_row(const std::string& key, const std::string& quantity, const std::string& ours, int sign)
  {
    const auto& v = source.at(key);
    rows.push_back({key, quantity, sign_text(static_cast<int>(v.low)), "the sign", ours,
                    verdict_of(sign == static_cast<int>(v.low)), RowKind::Sign});
  }

  void power_law_sign(const std::string& key, const std::string& quantity, const std::optional<PowerLaw>& law)
  {
    if (!law) return;
    sign_row(key, quantity,
             sign_text(sign_of(law->exponent)) + " (exponent " +
                 format_estimate(law->exponent.value, law->exponent.error) + ")",
             sign_of(law->exponent));
  }

  // A correlation over the runs having both results.
  std::optional<CorrelationTest> correlation_of(const std::string& x, const std::string& y) const
  {
    std::vector<double> xs, ys;
    for (const auto& run : series.runs) {
      auto yv = run.estimate(y), xv = run.estimate(x);
      if (xv && yv) xs.push_back(xv->value), ys.push_back(yv->value);
    }
    if (xs.size() < 3) return std::nullopt;
    try {
      return test_correlation(xs, ys);
    } catch (const std::exception&) {  // a constant series: no correlation
      return std::nullopt;
    }
  }

  void correlation_sign(const std::string& key, const std::string& quantity, const std::string& x, const std::string& y)
  {
    if (auto t = correlation_of(x, y))
      sign_row(key, quantity, sign_text(sign_of(*t)) + " (" + correlation_text(*t) + ")", sign_of(*t));
  }

  // The one estimator of the signs on mu and on L: y against ln x (ln mu, ln L) weighted by each
  // run's error of y, the sign of the slope beyond two of its errors (fit/linear_fit.h), with the
  // weighted fit and the unweighted correlation in words.
  struct WeightedPoints {
    std::vector<double> log_x, y, sigma;
  };
  void weighted_sign(const std::string& key, const std::string& quantity, const std::string& what,
                     const std::string& against, const WeightedPoints& p)
  {
    if (p.log_x.size() < 3) return;
    WeightedSlope fit;
    try {
      fit = fit_weighted_slope(p.log_x, p.y, p.sigma);
    } catch (const AnalysisError&) {  // one friction (one length) only: no slope
      return;
    }
    const int sign = sign_of(fit.slope);
    char reduced_chi2[32];
    std::snprintf(reduced_chi2, sizeof reduced_chi2, "%.2g", fit.reduced_chi2);
    sign_row(key, quantity,
             sign_text(sign) + " (slope of " + what + " against " + against +
                 ", weighted: " + format_estimate(fit.slope.value, fit.slope.error) + ", chi2/dof " + reduced_chi2 +
                 "; unweighted " + correlation_text(test_correlation(p.log_x, p.y)) + ")",
             sign);
  }

  // ln f about the law over every run, against ln mu: f set by mu leaves a residual that follows
  // mu. Each run weighted by its peak's half width at half power (the error of f) over f.
  void frequency_and_friction()
  {
    if (!series.f_vs_scale || frictions().size() < 2) return;
    const auto p = series.f_vs_scale->line.values();
    WeightedPoints points;
    for (const auto& run : series.runs)
      if (auto f = run.estimate("f"), x = run.estimate("f_scale"); f && x && f->error) {
        points.log_x.push_back(std::log(run.entry.mu));
        points.y.push_back(std::log(f->value) - (p[0] + p[1] * std::log(x->value)));
        points.sigma.push_back(*f->error / f->value);
      }
    weighted_sign("sign_f_vs_mu", "f at the same (sqrt(g d)/U g/d)^(1/2) against mu",
                  "ln f about the law over every run", "ln mu", points);
  }

  // ln A against ln mu, each run weighted by the error of its peak's amplitude: a Welch spectrum
  // averaging K segments has a power of relative error 1/sqrt(K), its amplitude half that.
  void amplitude_and_friction()
  {
    if (frictions().size() < 2) return;
    WeightedPoints points;
    for (const auto& run : series.runs)
      if (auto a = run.estimate("A"), segments = run.estimate("spectrum_segments");
          a && segments && a->value > 0 && segments->value > 0) {
        points.log_x.push_back(std::log(run.entry.mu));
        points.y.push_back(std::log(a->value));
        points.sigma.push_back(0.5 / std::sqrt(segments->value));
      }
    weighted_sign("sign_A_vs_mu", "A against mu (ln mu)", "ln A", "ln mu", points);
  }

  // Each run's decay of the amplitude at f with depth (a = a_s exp(z/lambda) in the layer).
  void depth()
  {
    int decays = 0, grows = 0, runs = 0;
    Spread lengths;
    for (const auto& run : series.runs)
      if (const auto& decay = run.depth_decay) {
        ++runs;
        lengths.add(decay->lambda.value);
        const int sign = sign_of(decay->lambda);
        decays += sign > 0, grows += sign < 0;
      }
    if (runs == 0) return;
    const int sign = decays == runs ? -1 : grows == runs ? 1 : 0;  // of A against depth
    sign_row("sign_A_vs_depth", "A against depth below the surface",
             sign_text(sign) + " (" + std::to_string(decays) + " of " + std::to_string(runs) +
                 " runs decay downward, lambda " + lengths.text() + " d)",
             sign);
  }

  // `constructed`: every run was made to have the source's value, so its spread is shown, not compared.
  void range_row(const std::string& key, const std::string& result, const std::string& quantity,
                 bool constructed = false)
  {
    Spread spread;
    for (const auto& run : series.runs)
      if (auto e = run.estimate(result)) spread.add(e->value);
    if (spread.empty()) return;
    const auto& v = source.at(key);
    rows.push_back({key, quantity, source_text(v), accepted_text(v) + " at every run", spread.text() + " " + v.unit,
                    constructed ? Verdict::ByConstruction : verdict_of(spread.within(v))});
  }

  bool thickness_set_by_deck() const
  {
    return std::all_of(series.runs.begin(), series.runs.end(),
                       [](const SeriesRun& run) { return run.thickness_set_by_deck; });
  }

  // A creep length over the runs: the median of the runs' `result`; compared, or shown beside.
  void creep_length(const std::string& result, const std::string& quantity, bool compared)
  {
    std::vector<double> lengths;
    for (const auto& run : series.runs)
      if (auto e = run.estimate(result)) lengths.push_back(e->value);
    if (lengths.empty()) return;
    std::sort(lengths.begin(), lengths.end());
    const size_t n = lengths.size();
    const double median = n % 2 ? lengths[n / 2] : 0.5 * (lengths[n / 2 - 1] + lengths[n / 2]);
    const auto& v = source.at("creep_length");
    rows.push_back({compared ? "creep_length" : "creep_length_" + result, quantity, source_text(v), accepted_text(v),
                    number(median) + " d (runs " + number(lengths.front()) + " to " + number(lengths.back()) + ")",
                    compared ? verdict_of(v.accepts(median)) : Verdict::Shown});
  }

  // The source's 2.5 d is a guide line on a semi-log inset, so the decay over the first decade
  // below the wall tops is compared; the fit down to ten times the floor (doc/creep.md) is shown.
  void creep()
  {
    creep_length("creep_lambda_first_decade",
                 "creep length below the wall tops as a guide line reads it: semi-log fit over the first decade of u "
                 "(median of the runs)",
                 true);
    creep_length("creep_lambda",
                 "creep length below the wall tops down to 10 x the floor, doc/creep.md (median of the runs)", false);
  }

  void angles()
  {
    for (double mu : frictions()) {
      const std::string key = "angles" + friction_suffix(mu);
      if (!source.has(key)) continue;
      Spread spread;
      for (const auto& run : series.runs)
        if (run.entry.mu == mu) spread.add(run.entry.theta_deg);
      rows.push_back({key, "angles run, " + mu_text(mu), source_text(source.at(key)), "–", spread.text() + " deg",
                      Verdict::Shown});
    }
  }

  // f against L weighted as f on mu is (each run by its peak's half width over f), over the runs
  // with an L; A_mean, which carries no error, by the exponent of its power law.
  void cell_length()
  {
    WeightedPoints points;
    for (const auto& run : series.runs)
      if (auto f = run.estimate("f"); run.entry.length_d && f && f->error && f->value > 0) {
        points.log_x.push_back(std::log(*run.entry.length_d));
        points.y.push_back(std::log(f->value));
        points.sigma.push_back(*f->error / f->value);
      }
    weighted_sign("sign_f_vs_L", "f against L", "ln f", "ln L", points);
    if (const auto* e = fit("A_mean_vs_L_exponent"))
      sign_row(
          "sign_A_mean_vs_L", "A_mean against L",
          sign_text(sign_of(Estimate{e->value, e->error})) + " (exponent " + format_estimate(e->value, e->error) + ")",
          sign_of(Estimate{e->value, e->error}));
  }
};

}  // namespace

std::vector<SourceRow> compare_with_source(const SeriesAnalysis& series)
{
  if (!series.source) return {};
  Comparer c{series, *series.source, {}};
  c.flow_rules();
  c.packing();
  c.range_row("f", "f", "peak frequency f of v(t)");
  c.power_law_sign("sign_f_vs_scale", "f against (sqrt(g d)/U g/d)^(1/2)", series.f_vs_scale);
  c.power_law_sign("sign_f_vs_shear_rate", "f against U/h", series.f_vs_shear_rate);
  c.frequency_and_friction();
  c.correlation_sign("sign_A_vs_U", "peak amplitude A against U", "U", "A");
  c.amplitude_and_friction();
  c.correlation_sign("sign_A_vs_phi", "A against phi", "phi", "A");
  c.depth();
  c.creep();
  c.range_row("h", "h", "flowing layer thickness h", c.thickness_set_by_deck());
  c.angles();
  c.cell_length();
  return grouped(c.rows);
}

std::vector<DegenerateRow> degenerate_parameters(const SeriesAnalysis& series)
{
  std::vector<DegenerateRow> rows;
  if (!series.source) return rows;
  const auto& source = *series.source;
  auto add = [&](const std::string& name, const std::string& correlation) {
    const auto* ours = series.fits.find(name);
    const auto* corr = series.fits.find(correlation);
    if (!ours || !source.has(name)) return;
    rows.push_back({name, source_text(source.at(name)), format_estimate(ours->value, ours->error),
                    corr ? number(corr->value) : "–"});
  };
  for (double mu : source.frictions) {
    const auto s = friction_suffix(mu);
    for (const std::string stem : {"pouliquen_theta1", "pouliquen_theta2", "pouliquen_ell"})
      add(stem + s, "pouliquen_corr_theta2_ell" + s);
  }
  const std::string first = source.frictions.empty() ? "" : friction_suffix(source.frictions.front());
  add("muI_I0", "muI_corr_I0_theta2" + first);
  for (double mu : source.frictions) {
    const auto s = friction_suffix(mu);
    for (const std::string stem : {"muI_theta1", "muI_theta2"}) add(stem + s, "muI_corr_I0_theta2" + s);
  }
  return rows;
}

namespace {

// The rows of every series merged by key, in the order of their first appearance.
struct MergedRow {
  const SourceRow* first = nullptr;
  std::vector<const SourceRow*> per_series;
};

std::vector<MergedRow> merged(const std::vector<std::vector<SourceRow>>& rows)
{
  std::vector<MergedRow> out;
  for (size_t s = 0; s < rows.size(); ++s)
    for (const auto& row : rows[s]) {
      auto found = std::find_if(out.begin(), out.end(), [&](const MergedRow& m) { return m.first->key == row.key; });
      if (found == out.end())
        found = out.insert(out.end(), MergedRow{&row, std::vector<const SourceRow*>(rows.size())});
      found->per_series[s] = &row;
    }
  return out;
}

std::vector<std::vector<SourceRow>> rows_of(const std::vector<LabelledSeries>& series)
{
  std::vector<std::vector<SourceRow>> rows;
  for (const auto& s : series) rows.push_back(compare_with_source(*s.series));
  return rows;
}

std::string verdicts_text(const MergedRow& row, const std::vector<LabelledSeries>& series)
{
  std::string text;
  for (size_t s = 0; s < series.size(); ++s) {
    const auto* r = row.per_series[s];
    if (!r) continue;
    text += (text.empty() ? "" : "; ") + (series.size() > 1 ? series[s].label + " " : "") + verdict_text(*r);
  }
  return text;
}

// "quantities a of n agree, signs b of m, set by construction: k".
std::string tally(const std::vector<SourceRow>& rows)
{
  int quantities = 0, quantities_agree = 0, signs = 0, signs_agree = 0, constructed = 0;
  for (const auto& r : rows) {
    const bool compared = r.verdict == Verdict::Agrees || r.verdict == Verdict::Outside;
    const bool agrees = r.verdict == Verdict::Agrees;
    if (compared && r.kind == RowKind::Sign) ++signs, signs_agree += agrees;
    else if (compared) ++quantities, quantities_agree += agrees;
    constructed += r.verdict == Verdict::ByConstruction;
  }
  return "quantities " + std::to_string(quantities_agree) + " of " + std::to_string(quantities) + ", signs " +
         std::to_string(signs_agree) + " of " + std::to_string(signs) + ", set by construction " +
         std::to_string(constructed);
}

std::string two_decimals(double value)
{
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", value);
  return text;
}

void inertial_check_table(MarkdownReport& report, const SourceNumbers& source)
{
  const auto checks = source_inertial_numbers(source);
  if (checks.empty()) return;
  std::vector<std::vector<std::string>> rows;
  double low = INFINITY, high = -INFINITY;
  for (const auto& c : checks) {
    const double bagnold = *pouliquen_inertial_as(c, "I_bagnold");
    low = std::min(low, c.mu_of_i / bagnold), high = std::max(high, c.mu_of_i / bagnold);
    rows.push_back({number(c.mu), number(c.theta_deg), number(c.pouliquen), number(c.mu_of_i),
                    two_decimals(c.mu_of_i / c.pouliquen), two_decimals(c.bagnold_factor), number(bagnold),
                    two_decimals(c.mu_of_i / bagnold)});
  }
  auto verdict = [&](const std::string& result) {
    return *rules_consistent(checks, result)
               ? std::string("agree within a factor 1.5 at every angle")
               : "disagree by more than a factor 1.5 (the I0 that would reconcile them, the geometric mean over "
                 "these angles: " +
                     number(reconciling_i0(source, checks, result)) + " against the stated " +
                     number(source.value("muI_I0")) + ")";
  };
  report.paragraph(
      "The source's two flow rules checked against each other at its own angles, with the parameters of " +
      source.path +
      ": the inertial number each gives, Pouliquen's I = beta / (l ln((tan theta2 - tan theta1)/(tan theta - tan "
      "theta1))) and the mu(I) rule's I = I0 (tan theta - tan theta1)/(tan theta2 - tan theta). Read as the stated I "
      "= d U/(sqrt(g) h^1.5) both, they " +
      verdict("I") +
      ". Pouliquen's rule is stated in U and h, so its I is the stated one; read as GDR MiDi's I = gamma_dot "
      "d/sqrt(P/rho) of a Bagnold layer, it is that I times 2.5/sqrt(phi cos theta) (fit/inertial_number.h; phi from "
      "the source's phi(U) law at the rule's U = I h^1.5, h the middle of its range of h), and the two rules " +
      verdict("I_bagnold") + ": mu(I)'s I over it " + two_decimals(low) + " to " + two_decimals(high) +
      ". A curve is a target under a reading of I with which the source's two rules agree; under one with which they "
      "disagree it is not, and under the local I, which the source's numbers cannot give, it is shown.");
  report.table({"mu", "theta (deg)", "I, Pouliquen", "I, mu(I)", "mu(I) / Pouliquen", "2.5/sqrt(phi cos theta)",
                "Pouliquen's I as GDR MiDi's", "mu(I) / that"},
               rows);
}

std::string definitions_text()
{
  std::string text;
  for (const auto& d : kInertialDefinitions) text += (text.empty() ? "" : "; ") + d.result + ": " + d.name;
  return text;
}

}  // namespace

void source_section(MarkdownReport& report, const std::vector<LabelledSeries>& series)
{
  if (series.empty() || !series.front().series->source) return;
  const auto& source = *series.front().series->source;
  const auto rows = rows_of(series);
  report.heading("Against the source");
  std::string tallies;
  for (size_t s = 0; s < series.size(); ++s) tallies += (s ? ", " : "") + series[s].label + " " + tally(rows[s]);
  report.paragraph(
      "The numbers of " + source.path +
      " beside this analysis (surface definition: h = 2 <z>, phi over the grains above the wall tops). Curves are "
      "compared as curves: each run's angle against the angle the source's rule gives at the run's I (and U against "
      "the rule's U at the run's own theta and h), each run's phi against the source's phi(U) law at its U. Ranges "
      "hold for every run. A sign is the exponent's beyond two standard errors, or a correlation's with p < 0.05; "
      "the signs with mu and with L are one weighted estimator: the slopes of ln f (about the law) and ln A "
      "against ln mu, and of ln f against ln L, each run weighted by its peak's error, beyond two of their errors. The "
      "flow rules are drawn against each reading of a run's I (" +
      definitions_text() +
      "). Quantities compared with a tolerance and signs are counted apart, and a row the runs were made to match "
      "(h, when every run's deck chose its grain count for it) is not compared. Agreeing: " +
      tallies + ".");
  std::vector<std::string> header{"quantity", "source"};
  for (const auto& s : series) header.push_back(s.label);
  header.insert(header.end(), {"tolerance", "verdict"});
  std::vector<std::vector<std::string>> table;
  for (const auto& row : merged(rows)) {
    std::vector<std::string> cells{row.first->quantity, row.first->source};
    for (const auto* r : row.per_series) cells.push_back(r ? r->ours : "–");
    cells.insert(cells.end(), {row.first->tolerance, verdicts_text(row, series)});
    table.push_back(cells);
  }
  report.table(header, table);
  report.paragraph(
      "The fitted parameters themselves are degenerate: over the runs' few angles a 3-parameter rule trades theta2 "
      "against l (Pouliquen) or I0 (mu(I)) along a valley (correlation near 1), so they are shown apart, not "
      "compared.");
  std::vector<std::string> degenerate_header{"parameter (degenerate)", "source"};
  std::vector<std::vector<DegenerateRow>> degenerate;
  for (const auto& s : series) {
    degenerate.push_back(degenerate_parameters(*s.series));
    degenerate_header.push_back(s.label);
    degenerate_header.push_back(s.label + ": correlation of theta2 with l or I0");
  }
  std::vector<std::vector<std::string>> degenerate_table;
  for (size_t i = 0; i < degenerate.front().size(); ++i) {
    std::vector<std::string> cells{degenerate.front()[i].name, degenerate.front()[i].source};
    for (const auto& d : degenerate) {
      const bool has = i < d.size() && d[i].name == degenerate.front()[i].name;
      cells.push_back(has ? d[i].ours : "–");
      cells.push_back(has ? d[i].correlation : "–");
    }
    degenerate_table.push_back(cells);
  }
  if (!degenerate_table.empty()) report.table(degenerate_header, degenerate_table);
  inertial_check_table(report, source);
}

namespace {

// One run under one reading of its I: the angle offsets from both of the source's rules there.
struct ReadingOffset {
  const SeriesRun* run = nullptr;
  const InertialDefinition* definition = nullptr;
  Estimate inertial;
  double pouliquen = 0, mu_of_i = 0;  // theta - theta_source(I), deg
};

std::vector<ReadingOffset> reading_offsets(const SeriesAnalysis& series)
{
  std::vector<ReadingOffset> offsets;
  if (!series.source) return offsets;
  const auto& source = *series.source;
  for (const auto& run : series.runs) {
    const double mu = run.entry.mu, theta = run.entry.theta_deg;
    if (std::find(source.frictions.begin(), source.frictions.end(), mu) == source.frictions.end()) continue;
    for (const auto& definition : kInertialDefinitions)
      if (auto inertial = run.estimate(definition.result))
        offsets.push_back({&run, &definition, *inertial, theta - pouliquen_angle(source, mu, inertial->value),
                           theta - mu_of_i_angle(source, mu, inertial->value)});
  }
  return offsets;
}

}  // namespace

void inertial_readings_section(MarkdownReport& report, const SeriesAnalysis& series)
{
  const auto offsets = reading_offsets(series);
  if (offsets.empty()) return;
  report.heading("The source's flow rules under each I");
  report.paragraph(
      "Each run's tilt minus the tilt each of the source's rules gives at the run's I, the I read three ways (" +
      definitions_text() +
      "; fit/inertial_number.h). Whether the source's own two rules agree under each reading: the table at the end "
      "of *Against the source*. Per run: inertial_readings.csv; figure flow_rules_by_I.");
  std::vector<std::vector<std::string>> rows;
  for (const auto& o : offsets)
    rows.push_back({o.run->entry.name, number(o.run->entry.mu), number(o.run->entry.theta_deg), o.definition->result,
                    format_estimate(o.inertial.value, o.inertial.error), two_decimals(o.pouliquen),
                    two_decimals(o.mu_of_i)});
  report.table({"run", "mu", "theta (deg)", "reading of I", "I", "theta - Pouliquen's (deg)", "theta - mu(I)'s (deg)"},
               rows);
}

void write_inertial_readings(const SeriesAnalysis& series, const std::string& path)
{
  const auto offsets = reading_offsets(series);
  if (offsets.empty()) return;
  auto out = open_output(path);
  out.precision(10);
  out << "run,mu,theta_deg,reading,I,I_error,theta_minus_pouliquen_deg,theta_minus_muI_deg\n";
  for (const auto& o : offsets) {
    out << o.run->entry.name << ',' << o.run->entry.mu << ',' << o.run->entry.theta_deg << ',' << o.definition->result
        << ',' << o.inertial.value << ',';
    if (o.inertial.error) out << *o.inertial.error;
    out << ',' << o.pouliquen << ',' << o.mu_of_i << '\n';
  }
}

void write_source_comparison(const std::vector<LabelledSeries>& series, const std::string& path)
{
  if (series.empty() || !series.front().series->source) return;
  auto out = open_output(path);
  out << "key,quantity,source";
  for (const auto& s : series) out << ',' << s.label;
  out << ",tolerance";
  for (const auto& s : series) out << ",verdict_" << s.label;
  out << '\n';
  auto quoted = [](const std::string& text) {
    std::string q = "\"";
    for (char c : text) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
  };
  const auto rows = rows_of(series);  // merged() points into them
  for (const auto& row : merged(rows)) {
    out << row.first->key << ',' << quoted(row.first->quantity) << ',' << quoted(row.first->source);
    for (const auto* r : row.per_series) out << ',' << quoted(r ? r->ours : "");
    out << ',' << quoted(row.first->tolerance);
    for (const auto* r : row.per_series) out << ',' << (r ? verdict_text(*r) : "");
    out << '\n';
  }
}

std::vector<FrictionCurve> source_velocity_points(const SeriesAnalysis& series, const std::string& thickness)
{
  std::vector<FrictionCurve> curves;
  if (!series.source) return curves;
  for (double mu : series.source->frictions) {
    Curve curve;
    curve.title = "source's Pouliquen, mu = " + number(mu);  // at each run's theta and h
    curve.style = CurveStyle::Points;
    curve.point_type = 6;  // open circles
    for (const auto& run : series.runs)
      if (auto h = run.estimate(thickness); run.entry.mu == mu && h)
        if (auto inertial = pouliquen_inertial(*series.source, mu, run.entry.theta_deg)) {
          curve.x.push_back(run.entry.theta_deg);
          curve.y.push_back(*inertial * std::pow(h->value, 1.5));
        }
    if (!curve.x.empty()) curves.push_back({mu, curve});
  }
  return curves;
}

std::vector<FrictionCurve> source_phi_lines(const SourceNumbers& source, double u0, double u1)
{
  std::vector<FrictionCurve> curves;
  for (double mu : source.frictions) {
    Curve line;
    line.title = "source's law, mu = " + number(mu);
    line.style = CurveStyle::LinesPoints;
    line.point_type = 3;  // asterisks: the source's, not a fit
    line.dashed = true;
    const double phi_c = source.value("phi_c" + friction_suffix(mu)), k = source.value("phi_k");
    for (int i = 0; i <= 4; ++i) {
      const double u = u0 + (u1 - u0) * i / 4;
      line.x.push_back(u), line.y.push_back(phi_c - k * u);
    }
    curves.push_back({mu, line});
  }
  return curves;
}

std::vector<Curve> source_frequency_range(const SourceNumbers& source, double x0, double x1)
{
  const auto& f = source.at("f");
  std::vector<Curve> lines;
  for (double level : {f.low, f.high}) {
    Curve line;
    line.title = level == f.low ? "source's range of f: " + source_text(f) : "";
    line.style = CurveStyle::Lines;
    line.dashed = true;
    line.line_type = 8;  // one colour for both bounds
    line.x = {x0, x1};
    line.y = {level, level};
    lines.push_back(line);
  }
  return lines;
}

std::vector<FrictionCurve> source_rule_curves(const SourceNumbers& source, double i0, double i1)
{
  std::vector<FrictionCurve> curves;
  using Rule = double (*)(const SourceNumbers&, double, double);
  for (double mu : source.frictions)
    for (const auto& [name, rule] :
         {std::pair<std::string, Rule>{"Pouliquen", pouliquen_angle}, {"mu(I)", mu_of_i_angle}}) {
      Curve curve;
      curve.title = "source's " + name + ", mu = " + number(mu);
      curve.style = CurveStyle::Lines;
      curve.dashed = rule == pouliquen_angle;
      for (int i = 0; i <= 100; ++i) {
        const double inertial = i0 + (i1 - i0) * i / 100.0;
        curve.x.push_back(inertial);
        curve.y.push_back(rule(source, mu, inertial));
      }
      curves.push_back({mu, curve});
    }
  return curves;
}

}  // namespace cdpost
