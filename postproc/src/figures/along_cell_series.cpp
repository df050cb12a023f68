#include "figures/along_cell_series.h"

#include "analysis/along_cell.h"

namespace cdpost {

namespace {

// The results written per run, in this order, each with its error.
const std::vector<std::string> kColumns = {
    "coherence_length",      "coherence_plateau",  "coherence_far", "wavenumber_uniform_fraction",
    "wavenumber_dominant_m", "wavenumber_balance", "phase_velocity"};

std::string verdict_of(const SeriesRun& run)
{
  const auto code = run.estimate("oscillation_pattern");
  return code ? pattern_name(code->value).value_or("unknown code") : "";
}

std::string cell(const std::optional<Estimate>& e)
{
  return e ? format_estimate(e->value, e->error) : "–";
}

void write_csv(const SeriesAnalysis& series, const std::string& path)
{
  auto out = open_output(path);
  out.precision(10);
  out << "run,mu,theta_deg,pattern";
  for (const auto& name : kColumns) out << ',' << name << ',' << name << "_error";
  out << '\n';
  for (const auto& run : series.runs) {
    if (verdict_of(run).empty()) continue;
    out << run.entry.name << ',' << run.entry.mu << ',' << run.entry.theta_deg << ',' << verdict_of(run);
    for (const auto& name : kColumns) {
      const auto e = run.estimate(name);
      out << ',';
      if (e) out << e->value;
      out << ',';
      if (e && e->error) out << *e->error;
    }
    out << '\n';
  }
}

Panel against_velocity(const SeriesAnalysis& series, const std::string& y, const std::string& y_label, double width,
                       double origin)
{
  Panel panel;
  panel.title = y_label + " against U";
  panel.x_label = "U / sqrt(g d)";
  panel.y_label = y_label;
  panel.curves = by_friction(series, "U", y);
  panel.width = width;
  panel.origin_x = origin;
  return panel;
}

}  // namespace

void along_cell_section(SeriesAnalysis& series, MarkdownReport& report, const std::string& out_dir)
{
  report.heading("Where the oscillation lives along the cell");
  std::vector<std::vector<std::string>> rows;
  for (const auto& run : series.runs)
    if (!verdict_of(run).empty())
      rows.push_back({run.entry.name, verdict_of(run), cell(run.estimate("coherence_length")),
                      cell(run.estimate("coherence_far")), cell(run.estimate("wavenumber_uniform_fraction")),
                      cell(run.estimate("wavenumber_dominant_m")), cell(run.estimate("wavenumber_balance")),
                      cell(run.estimate("phase_velocity"))});
  if (rows.empty()) {
    report.paragraph("No run has the along-cell analysis (columns.chunk and the cell length).");
    return;
  }
  report.paragraph(
      "Per run, from v(x, t) in columns (each run's report gives the method): the verdict, the coherence length xi "
      "(d; – where the coherence does not decay within the cell), the coherence at the largest distance, the share "
      "of m = 0 in the power at f, the dominant |m| signed by its stronger direction, its balance and, for a "
      "travelling wave, the phase velocity (sqrt(g d)). All of them in along_cell.csv.");
  report.table({"run", "verdict", "xi (d)", "C far", "m = 0 share", "m", "balance", "c (sqrt(g d))"}, rows);
  write_csv(series, out_dir + "/along_cell.csv");
  // Against U, per friction: whether the coherence, not only the amplitude, changes with the flow's speed.
  auto far = against_velocity(series, "coherence_far", "coherence at the largest distance", 0.5, 0.5);
  far.y_range = std::make_pair(0.0, 1.05);
  Figure figure{"coherence_vs_U",
                "Coherence length (where it is determined) and coherence at the largest distance against U",
                {far},
                1300,
                600};
  auto lengths = against_velocity(series, "coherence_length", "xi / d", 0.5, 0);
  if (!lengths.curves.empty()) figure.panels.push_back(lengths);
  if (auto problem = render_figure(figure, out_dir + "/figures")) series.warnings.push_back(*problem);
  else report.figure("figures", figure.name, figure.caption);
}

}  // namespace cdpost
