// The comparison's figures: spectra, peaks and bulk quantities against k, U(t), u(z), cost.
#include "comparison_figures.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>

#include "comparison_tables.h"

namespace cdref {

using cdpost::Curve;
using cdpost::CurveStyle;
using cdpost::Figure;
using cdpost::make_curve;
using cdpost::Panel;

namespace {

// A panel of the comparison, its key outside the plot on the right (a key for every run).
Panel keyed_panel(const std::string& title, const std::string& x_label, const std::string& y_label)
{
  Panel panel;
  panel.title = title;
  panel.x_label = x_label;
  panel.y_label = y_label;
  panel.key = "outside right top";
  return panel;
}

// Spectra of v(t) on log-log axes, with a vertical line at each soft run's contact frequency.
Figure spectra_figure(const std::vector<const ComparedRun*>& runs, const std::string& name, const std::string& title)
{
  Panel panel = keyed_panel(title, "f (Hz)", "A / sqrt(g d)");
  panel.log_x = panel.log_y = true;
  double lo = INFINITY, hi = 0;
  for (const auto* r : runs) {
    std::vector<double> f, a;
    const auto& s = r->analysis.spectrum;
    for (size_t k = 1; k < s.frequency_hz.size(); ++k)
      if (s.amplitude[k] > 0) {
        f.push_back(s.frequency_hz[k]);
        a.push_back(s.amplitude[k]);
        lo = std::min(lo, s.amplitude[k]);
        hi = std::max(hi, s.amplitude[k]);
      }
    panel.curves.push_back(make_curve(r->label, CurveStyle::Lines, f, a));
  }
  if (hi > 0)
    for (const auto* r : runs)
      if (r->f_contact_hz)
        panel.curves.push_back(make_curve("f_c " + r->label + " = " + short_number(*r->f_contact_hz) + " Hz",
                                          CurveStyle::Lines, {*r->f_contact_hz, *r->f_contact_hz}, {lo, hi}));
  return {name, title, {panel}, 1200, 650};
}

Figure peaks_figure(const Comparison& c)
{
  Panel panel = keyed_panel("Spectral peaks against stiffness (lines: sqrt(2k/m)/(2 pi); rigid runs drawn flat)",
                            "k / (m g / d)", "f (Hz)");
  panel.log_x = panel.log_y = true;
  std::map<std::string, std::pair<Curve, Curve>> by_group;
  double kmin = INFINITY, kmax = 0;
  std::optional<double> k_to_f;  // f_c / sqrt(k_reduced), the same for every soft run of one d
  for (const auto& r : c.runs) {
    if (!r.soft() || !r.k_reduced) continue;
    kmin = std::min(kmin, *r.k_reduced);
    kmax = std::max(kmax, *r.k_reduced);
    k_to_f = *r.f_contact_hz / std::sqrt(*r.k_reduced);
    auto& [contact, flow] = by_group[code_name(r.code) + " " + r.model];
    contact.style = flow.style = CurveStyle::ErrorBars;
    if (r.contact_peak) {
      contact.x.push_back(*r.k_reduced);
      contact.y.push_back(r.contact_peak->frequency_hz);
      contact.y_error.push_back(r.contact_peak->frequency_error_hz);
    }
    if (r.flow_peak) {
      flow.x.push_back(*r.k_reduced);
      flow.y.push_back(r.flow_peak->frequency_hz);
      flow.y_error.push_back(r.flow_peak->frequency_error_hz);
    }
  }
  for (auto& [group, curves] : by_group) {
    curves.first.title = group + ": contact-band peak";
    curves.second.title = group + ": flow-band peak";
    if (!curves.first.x.empty()) panel.curves.push_back(curves.first);
    if (!curves.second.x.empty()) panel.curves.push_back(curves.second);
  }
  if (k_to_f && kmax > 0) {
    std::vector<double> k{kmin / 2, kmax * 2};
    panel.curves.push_back(
        make_curve("sqrt(2k/m)/(2 pi)", CurveStyle::Lines, k, {*k_to_f * std::sqrt(k[0]), *k_to_f * std::sqrt(k[1])}));
    for (const auto& r : c.runs)
      if (r.model == "rigid" && r.flow_peak)
        panel.curves.push_back(make_curve(r.label + ": flow-band peak", CurveStyle::Lines, k,
                                          {r.flow_peak->frequency_hz, r.flow_peak->frequency_hz}));
  }
  return {"peaks_vs_k", "Where the spectral peaks sit as k changes", {panel}, 1100, 650};
}

// The smallest and largest reduced stiffness of the runs that have one (INFINITY and 0 when none
// has): flat lines of runs without k are drawn over [kmin / 2, 2 kmax].
std::pair<double, double> k_span(const Comparison& c)
{
  double kmin = INFINITY, kmax = 0;
  for (const auto& r : c.runs)
    if (r.k_reduced) {
      kmin = std::min(kmin, *r.k_reduced);
      kmax = std::max(kmax, *r.k_reduced);
    }
  return {kmin, kmax};
}

Figure bulk_figure(const Comparison& c)
{
  Figure figure{"bulk_vs_k", "U, phi and h of every run against stiffness (rigid runs drawn flat)", {}, 900, 1000};
  const char* names[3] = {"U", "phi", "h"};
  const char* labels[3] = {"U / sqrt(g d)", "phi", "h / d"};
  const auto [kmin, kmax] = k_span(c);
  if (!(kmax > 0)) return figure;
  for (int i = 0; i < 3; ++i) {
    Panel p = keyed_panel(names[i], "k / (m g / d)", labels[i]);
    p.log_x = true;
    p.height = 1.0 / 3;
    p.origin_y = (2 - i) / 3.0;
    std::map<std::string, Curve> groups;
    for (const auto& r : c.runs) {
      auto v = result_value(r, names[i]);
      if (!v) continue;
      if (r.model == "rigid" || !r.k_reduced) {
        p.curves.push_back(make_curve(r.label, CurveStyle::Lines, {kmin / 2, kmax * 2}, {*v, *v}));
        continue;
      }
      auto& g = groups[code_name(r.code) + " " + r.model];
      g.title = code_name(r.code) + " " + r.model;
      g.style = CurveStyle::ErrorBars;
      g.x.push_back(*r.k_reduced);
      g.y.push_back(*v);
      g.y_error.push_back(result_error(r, names[i]).value_or(0));
    }
    for (auto& [name, g] : groups) p.curves.push_back(g);
    if (!p.curves.empty()) figure.panels.push_back(p);
  }
  return figure;
}

Figure profiles_figure(const Comparison& c)
{
  Panel panel = keyed_panel("Velocity profiles u(z) over each run's window", "u / sqrt(g d)", "z / d");
  for (const auto& r : c.runs)
    if (r.analysis.profile)
      panel.curves.push_back(
          make_curve(r.label, CurveStyle::LinesPoints, r.analysis.profile->u_reduced, r.analysis.profile->z_d));
  return {"profiles", "u(z) of every run", {panel}, 1100, 700};
}

Figure u_t_figure(const Comparison& c)
{
  Panel panel = keyed_panel("U(t): mean x-velocity of the grains with z > 0", "t / sqrt(d/g)", "U / sqrt(g d)");
  for (const auto& r : c.runs) {
    const auto& u = r.analysis.settings.units;
    std::vector<double> t, v;
    const auto& s = r.analysis.series;
    const size_t stride = std::max<size_t>(1, s.time_s.size() / 2000);
    for (size_t i = 0; i < s.time_s.size(); i += stride) {
      t.push_back(s.time_s[i] / u.reduced_time_s());
      v.push_back(s.u_flow_mps[i] / u.reduced_velocity_mps());
    }
    panel.curves.push_back(make_curve(r.label, CurveStyle::Lines, t, v));
  }
  return {"u_t", "U(t) of every run", {panel}, 1100, 600};
}

Figure cost_figure(const Comparison& c)
{
  Panel panel =
      keyed_panel("Cost per physical second: wall time, and wall time x the process's CPU share (rigid: flat lines)",
                  "k / (m g / d)", "s / physical s");
  panel.log_x = panel.log_y = true;
  const auto [kmin, kmax] = k_span(c);
  using Metric = std::optional<double> (ComparedRun::*)() const;
  const std::pair<const char*, Metric> metrics[2] = {{"wall", &ComparedRun::wall_per_physical_second},
                                                     {"CPU", &ComparedRun::cpu_per_physical_second}};
  for (const auto& [metric, cost_of] : metrics) {
    std::map<std::string, std::vector<std::pair<double, double>>> groups;
    for (const auto& r : c.runs) {
      auto cost = (r.*cost_of)();
      if (!cost) continue;
      if (!r.k_reduced) {
        if (kmax > 0)
          panel.curves.push_back(
              make_curve(r.label + " " + metric, CurveStyle::Lines, {kmin / 2, kmax * 2}, {*cost, *cost}));
        continue;
      }
      groups[code_name(r.code) + " " + r.model].push_back({*r.k_reduced, *cost});
    }
    for (auto& [name, points] : groups) {
      std::sort(points.begin(), points.end());
      std::vector<double> k, cost;
      for (const auto& [x, y] : points) {
        k.push_back(x);
        cost.push_back(y);
      }
      panel.curves.push_back(make_curve(name + " " + metric, CurveStyle::LinesPoints, k, cost));
    }
  }
  return {"cost", "Cost of each model", {panel}, 1100, 600};
}

}  // namespace

std::vector<Figure> comparison_figures(const Comparison& comparison)
{
  std::vector<const ComparedRun*> all;
  std::map<std::string, std::vector<const ComparedRun*>> by_code;
  for (const auto& r : comparison.runs) {
    all.push_back(&r);
    if (r.model != "rigid") by_code[r.code].push_back(&r);
  }
  std::vector<Figure> figures{
      spectra_figure(all, "spectra", "Spectra of v(t), every run (vertical lines: contact frequencies)")};
  for (auto& [code, runs] : by_code) {
    std::vector<const ComparedRun*> with_rigid;
    for (const auto& r : comparison.runs)
      if (r.model == "rigid") with_rigid.push_back(&r);
    with_rigid.insert(with_rigid.end(), runs.begin(), runs.end());
    std::string stem = code;
    std::replace(stem.begin(), stem.end(), '-', '_');
    figures.push_back(spectra_figure(with_rigid, "spectra_" + stem, "Spectra of v(t): rigid and " + code_name(code)));
  }
  figures.push_back(peaks_figure(comparison));
  figures.push_back(u_t_figure(comparison));
  figures.push_back(profiles_figure(comparison));
  auto bulk = bulk_figure(comparison);
  if (!bulk.panels.empty()) figures.push_back(bulk);
  figures.push_back(cost_figure(comparison));
  return figures;
}

}  // namespace cdref
