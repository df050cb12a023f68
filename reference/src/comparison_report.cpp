// The comparison's report (OUT/report.md) and everything written beside it: the method in
// prose, the table, the fits, the runs, the figures and the commands.
#include <filesystem>
#include <fstream>
#include <sstream>

#include "comparison.h"
#include "comparison_figures.h"
#include "comparison_tables.h"
#include "io/line_source.h"
#include "output/report.h"

namespace cdref {

namespace fs = std::filesystem;

namespace {

std::string method_text(const CompareSettings& settings)
{
  std::ostringstream m;
  const auto& s = settings.run;
  m << "Each run directory is analysed as by `cdpost run` (doc/postproc.md): window = detected stationary regime "
       "(line fitted to U(t) drifting by at most "
    << short_number(s.criterion.max_relative_drift * 100) << "% over at least "
    << short_number(s.criterion.min_window_fraction * 100)
    << "% of the run) unless given; a run without one is analysed over its second half and marked *not stationary*. "
       "Spectra of v(t): Welch, Hann, segments of "
    << short_number(s.spectrum.segment_duration_s) << " s. f, A: highest peak above " << short_number(s.peak_fmin_hz)
    << " Hz; f_flow, A_flow: highest peak in [" << short_number(s.peak_fmin_hz) << ", "
    << short_number(settings.flow_band_max_hz) << "] Hz; f_contact_band, A_contact_band: highest peak in ["
    << short_number(settings.contact_band_low) << ", " << short_number(settings.contact_band_high)
    << "] x f_contact (capped at the Nyquist frequency): the spectrum smoothed over +-"
    << short_number(100 * settings.smoothing)
    << "% in frequency is compared with a power law fitted to it over the band (log-log); contact_excess is the "
       "largest ratio, and a peak (the highest bin of that feature) is reported when contact_excess >= "
    << short_number(settings.peak_excess)
    << ". A band maximum at an end of the flow band is no peak and is left out (\"-\"). f_contact = sqrt(2k/m)/(2 pi) "
       "with m the mass of a grain of diameter d and k the deck's stiffness (Hertz: the secant stiffness at the target "
       "overlap). Overlaps: every contact of every dump frame inside the window (grain pairs with the minimum image "
       "along x, grains and the floor), in d. Wall time per physical second: the last `Loop time` of the run's log "
       "(its flow stage; summed with those of the continuation runs in part2, part3, ... when the flow was run in "
       "parts) over the simulated time of those stages. cpu_per_physical_s: each loop's wall time times its process's "
       "CPU share, (user + sys)/wall from timing.txt (else LAMMPS's own CPU-use line): what the run would cost on a "
       "core of its own when other jobs shared the machine.";
  return m.str();
}

// One line per run: its window, step, sampling, overlaps and flow loop.
std::string runs_text(const Comparison& comparison)
{
  std::ostringstream runs;
  for (const auto& r : comparison.runs) {
    runs << "- **" << r.label << "** (`" << r.directory << "`): window " << r.window_note;
    if (const auto* t0 = r.analysis.results.find("t_start"))
      runs << ", t = " << short_number(t0->value) << "–" << short_number(r.analysis.results.find("t_end")->value)
           << " sqrt(d/g)";
    if (auto dt = r.info.number("dt")) runs << "; dt = " << short_number(*dt) << " s";
    if (auto sample = r.info.number("sample_interval")) runs << "; sampling " << short_number(*sample) << " s";
    if (r.overlaps)
      runs << "; overlaps over " << r.overlaps->frames << " frames, " << r.overlaps->contacts << " contacts, p99 "
           << short_number(r.overlaps->p99) << " d";
    if (r.loop_seconds)
      runs << "; flow loop " << short_number(*r.loop_seconds) << " s for " << short_number(*r.physical_seconds) << " s";
    runs << "\n";
  }
  return runs.str();
}

}  // namespace

void write_comparison(Comparison& comparison, const CompareSettings& settings, const std::string& out_dir)
{
  const std::string figures_dir = out_dir + "/figures";
  fs::create_directories(figures_dir);
  write_table_csv(comparison, out_dir + "/table.csv");
  comparison.fits.write_csv(out_dir + "/fits.csv");
  write_long_csvs(comparison, out_dir);

  const auto figures = comparison_figures(comparison);

  cdpost::MarkdownReport report("Rigid and soft-sphere runs of the chute, side by side");
  report.paragraph(method_text(settings));
  report.heading("Table");
  report.paragraph(markdown_table(comparison));
  report.heading("How the peaks move with k");
  report.table(comparison.fits);
  report.heading("Runs");
  report.paragraph(runs_text(comparison));
  report.heading("Figures");
  for (const auto& figure : figures) {
    if (auto problem = cdpost::render_figure(figure, figures_dir)) comparison.warnings.push_back(*problem);
    else report.figure("figures", figure.name, figure.caption);
  }
  if (!settings.commands_file.empty()) {
    std::ifstream in(settings.commands_file);
    if (!in) throw cdpost::InputError(settings.commands_file, 0, "cannot read the commands file");
    std::stringstream text;
    text << in.rdbuf();
    report.heading("Commands");
    report.paragraph("```\n" + text.str() + "```");
  }
  report.warnings(comparison.warnings);
  report.write(out_dir + "/report.md");
}

}  // namespace cdref
