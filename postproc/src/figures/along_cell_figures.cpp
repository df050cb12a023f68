// Tables, figure and report text of the along-cell analysis of one run.
#include "figures/along_cell_figures.h"

#include <algorithm>
#include <cmath>

namespace cdpost {

namespace {

std::string number(double value)
{
  return format_estimate(value, std::nullopt);
}

// The highest frequency the map shows: four times the peak, at most Nyquist.
size_t map_bins(const AlongCell& along)
{
  const auto& s = along.spectrum;
  return std::min(s.bins, static_cast<size_t>(std::ceil(4 * along.frequency_hz / s.resolution_hz)) + 1);
}

Curve lines(const std::string& title, std::vector<double> x, std::vector<double> y)
{
  Curve curve;
  curve.title = title;
  curve.style = CurveStyle::Lines;
  curve.x = std::move(x);
  curve.y = std::move(y);
  return curve;
}

Panel map_panel(const AlongCell& along)
{
  const auto& s = along.spectrum;
  double highest = 0;
  for (double p : s.power) highest = std::max(highest, p);
  const double lowest_shown = highest * 1e-8;  // eight decades below the maximum
  Curve map;
  map.style = CurveStyle::Map;
  for (int m = s.lowest_m(); m <= s.highest_m(); ++m) {
    if (m != s.lowest_m()) map.x.push_back(NAN), map.y.push_back(NAN), map.colour.push_back(NAN);
    for (size_t l = 0; l < map_bins(along); ++l) {
      map.x.push_back(s.wavenumber(m));
      map.y.push_back(s.frequency_hz(l));
      map.colour.push_back(std::log10(std::max(s.power_at(m, l), lowest_shown)));
    }
  }
  Panel panel;
  panel.title = "Power of v(x, t) (L = " + number(s.cell_length) + " d, " + std::to_string(s.columns) + " columns)";
  panel.x_label = "k d = 2 pi m d / L (> 0: along +x)";
  panel.y_label = "f (Hz)";
  panel.colour_label = "log10 (power / g d)";
  panel.key = "top right";
  const double half_step = M_PI / s.cell_length;
  panel.x_range = std::make_pair(s.wavenumber(s.lowest_m()) - half_step, s.wavenumber(s.highest_m()) + half_step);
  panel.y_range = std::make_pair(0.0, s.frequency_hz(map_bins(along) - 1));
  panel.curves.push_back(map);
  panel.curves.push_back(lines("peak f = " + number(along.frequency_hz) + " Hz",
                               {s.wavenumber(s.lowest_m()), s.wavenumber(s.highest_m())},
                               {along.frequency_hz, along.frequency_hz}));
  panel.width = 0.55;
  return panel;
}

Panel coherence_panel(const AlongCell& along)
{
  const auto& c = along.coherence;
  Panel panel;
  panel.title = "Coherence at f against distance: " + pattern_name(along.verdict.pattern);
  panel.x_label = "periodic distance r / d";
  panel.y_label = "magnitude-squared coherence";
  panel.key = "right center";
  panel.y_range = std::make_pair(0.0, 1.05);
  Curve measured;
  measured.title = "mean over the column pairs";
  measured.style = CurveStyle::Points;
  measured.x = c.distance;
  measured.y = c.coherence;
  panel.curves.push_back(measured);
  if (along.fit) {
    std::vector<double> r, fitted;
    for (int i = 0; i <= 100; ++i) {
      r.push_back(c.distance.back() * i / 100.0);
      fitted.push_back(fitted_coherence(*along.fit, c.noise_floor, r.back()));
    }
    const auto& xi = along.fit->length;
    panel.curves.push_back(lines(
        xi ? "fit, xi = " + format_estimate(xi->value, xi->error) + " d" : "fit (no significant decay)", r, fitted));
  }
  panel.curves.push_back(
      lines("noise floor " + number(c.noise_floor), {0, c.distance.back()}, {c.noise_floor, c.noise_floor}));
  panel.origin_x = 0.55;
  panel.width = 0.45;
  return panel;
}

}  // namespace

void write_along_cell_tables(const AlongCell& along, const std::string& out_dir)
{
  const auto& s = along.spectrum;
  std::vector<std::vector<double>> map(4);
  for (int m = s.lowest_m(); m <= s.highest_m(); ++m)
    for (size_t l = 0; l < s.bins; ++l) {
      map[0].push_back(m);
      map[1].push_back(s.wavenumber(m));
      map[2].push_back(s.frequency_hz(l));
      map[3].push_back(s.power_at(m, l));
    }
  write_columns_csv(out_dir + "/space_time.csv", {"m", "k_per_d", "f_Hz", "power_gd"}, map);
  const auto& c = along.coherence;
  std::vector<std::string> names{"r_d", "coherence", "pairs"};
  std::vector<std::vector<double>> columns{c.distance, c.coherence, {c.pairs.begin(), c.pairs.end()}};
  if (along.fit) {
    names.push_back("fitted");
    columns.emplace_back();
    for (double r : c.distance) columns.back().push_back(fitted_coherence(*along.fit, c.noise_floor, r));
  }
  write_columns_csv(out_dir + "/coherence.csv", names, columns);
}

Figure along_cell_figure(const AlongCell& along)
{
  return {"along_cell",
          "Where the oscillation lives along the cell: (k, f) power of v(x, t) and the coherence of v at f "
          "against distance; " +
              along.verdict.text,
          {map_panel(along), coherence_panel(along)},
          1400,
          600};
}

std::string along_cell_text(const AlongCell& along, const std::string& window)
{
  const auto& s = along.spectrum;
  const auto& c = along.coherence;
  return "v(x, t) of the flowing layer in " + std::to_string(s.columns) + " columns of " +
         number(s.cell_length / s.columns) + " d tiling the cell (columns.chunk), over the " + window +
         ". Space-time spectrum (space_time.csv): "
         "Welch in time (" +
         std::to_string(s.segments) + " Hann-windowed, detrended segments of " + number(s.segment_duration_s) +
         " s), periodic transform in x; the power at (m, f) is the mean a^2 of a wave a cos(2 pi (m x/L - f t)) "
         "(m > 0: along +x). Coherence (coherence.csv): magnitude-squared coherence of each column pair from the "
         "cross spectra summed over the segments and the " +
         std::to_string(c.band.size()) + " bins of the band at f = " + number(along.frequency_hz) + " Hz (" +
         number(c.averages) + " effective averages, noise floor " + number(c.noise_floor) +
         "), averaged over the pairs at each periodic distance. Coherence length xi: the fit of "
         "C(r) = (g_far + (g0 - g_far) exp(-r/xi))^2 (plateau g_far^2, c0 = g0^2), as its expected estimate "
         "C + (1 - C)^2 floor, over every "
         "distance (it uses every distance and separates a part coherent across the cell, where a 1/e crossing "
         "rests on two points); errors by jackknife over groups of segments" +
         (along.no_fit_reason.empty() ? "" : " (" + along.no_fit_reason + ")") + ". Verdict: " + along.verdict.text +
         ".";
}

}  // namespace cdpost
