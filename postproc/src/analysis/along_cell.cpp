#include "analysis/along_cell.h"

#include <algorithm>
#include <cmath>

#include "fit/nonlinear_fit.h"

namespace cdpost {

namespace {

// A column empty in more samples than this is too sparse for interpolation to be harmless.
constexpr double kMostEmptySamples = 0.05;
// One direction dominates when it holds at least twice the power of the other: |balance| >= 1/3.
constexpr double kTravellingBalance = 1.0 / 3;
// Neighbouring columns are incoherent when their mean coherence is below twice the noise floor
// (the mean of M pair estimates of incoherent columns scatters by ~floor / sqrt(M)).
constexpr double kIncoherentNeighbours = 2;
// Below this many averages incoherent columns read up to half or more (the floor 1/n, twice it
// 2/n >= 1/2), and a single segment reads 1 whatever the field: the coherence cannot tell
// coherent columns from incoherent ones, and no verdict rests on it.
constexpr double kLeastAverages = 4;
// The coherence is kept across the cell when its plateau is at least half that of neighbours.
constexpr double kCoherentPlateau = 0.5;
// The coherence fit's three parameters need more distances than that.
constexpr size_t kFitDistances = 4;
// m = 0 dominates when it holds at least half the power at f: more than every other m together.
constexpr double kUniformFraction = 0.5;

std::string number(double value)
{
  return format_estimate(value, std::nullopt);
}

// The expected estimate, from n = 1/floor averages, of the true coherence C(r) = gamma(r)^2
// with the coherency gamma(r) = g_far + (g0 - g_far) exp(-r / xi): C + (1 - C)^2 / n (Carter,
// Knapp & Nuttall 1973, to first order in 1/n), the floor where C vanishes, nothing added at 1.
double expected_estimate(double g0, double g_far, double inverse_length, double floor, double r)
{
  const double gamma = g_far + (g0 - g_far) * std::exp(-r * inverse_length);
  const double c = gamma * gamma;
  return c + (1 - c) * (1 - c) * floor;
}

// The coherencies are magnitudes of a correlation, 0 <= g <= 1: the fit varies angles a with
// g = sin(a)^2, which covers that range and no more. (Fitted as free numbers, g0 came out above 1
// where the measured coherence is near 1 at every distance: the model's extrapolation to r = 0.)
double coherency(double angle)
{
  return std::pow(std::sin(angle), 2);
}
double coherency_angle(double g)
{
  return std::asin(std::sqrt(std::clamp(g, 0.0, 1.0)));  // an initial guess from a measured value
}

// The samples of one column, its empty ones interpolated in time between the nearest occupied.
std::vector<double> filled_column(const std::vector<double>& v, const std::vector<bool>& occupied, size_t& filled)
{
  std::vector<size_t> known;
  for (size_t n = 0; n < v.size(); ++n)
    if (occupied[n]) known.push_back(n);
  std::vector<double> out(v);
  size_t next = 0;  // index in `known` of the first occupied sample at or after n
  for (size_t n = 0; n < v.size(); ++n) {
    while (next < known.size() && known[next] < n) ++next;
    if (occupied[n]) continue;
    ++filled;
    if (next == 0) out[n] = v[known.front()];
    else if (next == known.size()) out[n] = v[known.back()];
    else {
      const size_t a = known[next - 1], b = known[next];
      out[n] = v[a] + (v[b] - v[a]) * double(n - a) / double(b - a);
    }
  }
  return out;
}

void check_tiling(const ChunkSeries& chunks, size_t block, const ColumnsLayout& layout)
{
  const size_t columns = chunks.chunks;
  if (columns < 8)
    throw AnalysisError(chunks.source + ": " + std::to_string(columns) +
                        " columns, the coherence fit needs at least 8 (4 distances): narrow column_width");
  for (size_t j = 0; j < columns; ++j) {
    const double expected = (j + 0.5) / double(columns), coord = chunks.value(block, j, layout.coord);
    if (std::abs(coord - expected) > 1e-4)
      throw AnalysisError(chunks.source + ": column " + std::to_string(j + 1) +
                          " is centred at x/lx = " + number(coord) + ", not " + number(expected) +
                          ": the columns must tile the cell in reduced units (bin/1d x 0.0 1/M units reduced)");
  }
}

}  // namespace

std::string pattern_name(OscillationPattern pattern)
{
  switch (pattern) {
    case OscillationPattern::Uniform: return "uniform";
    case OscillationPattern::Standing: return "standing";
    case OscillationPattern::Travelling: return "travelling";
    case OscillationPattern::Local: return "local";
  }
  return "";
}

std::optional<std::string> pattern_name(double code)
{
  for (auto p : {OscillationPattern::Uniform, OscillationPattern::Standing, OscillationPattern::Travelling,
                 OscillationPattern::Local})
    if (code == static_cast<int>(p)) return pattern_name(p);
  return std::nullopt;
}

SpaceTimeField field_from_chunks(const ChunkSeries& chunks, const std::vector<size_t>& blocks,
                                 const ColumnsLayout& layout, double velocity_factor, double sample_interval_s,
                                 double cell_length_d, size_t& filled)
{
  if (blocks.empty()) throw AnalysisError(chunks.source + ": no sample in the window");
  check_tiling(chunks, blocks.front(), layout);
  SpaceTimeField field;
  field.sample_interval_s = sample_interval_s;
  field.cell_length = cell_length_d;
  filled = 0;
  for (size_t j = 0; j < chunks.chunks; ++j) {
    std::vector<double> v;
    std::vector<bool> occupied;
    for (size_t b : blocks) {
      v.push_back(chunks.value(b, j, layout.v) * velocity_factor);
      occupied.push_back(chunks.value(b, j, layout.count) > 0);
    }
    const auto empty = static_cast<double>(std::count(occupied.begin(), occupied.end(), false));
    if (empty > kMostEmptySamples * double(blocks.size()))
      throw AnalysisError(chunks.source + ": column " + std::to_string(j + 1) + " is empty in " +
                          number(100 * empty / double(blocks.size())) + " % of the samples (at most " +
                          number(100 * kMostEmptySamples) + " % can be interpolated): widen column_width");
    field.columns.push_back(filled_column(v, occupied, filled));
  }
  return field;
}

double fitted_coherence(const CoherenceFit& fit, double floor, double distance)
{
  return expected_estimate(fit.g0, fit.g_far, fit.inverse_length.value, floor, distance);
}

namespace {

// The angles of the coherencies g0, g_far and 1/xi fitted to `measured` (see CoherenceFit).
FitResult fit_decay(const std::vector<double>& r, const std::vector<double>& measured, double floor)
{
  auto model = [&](const std::vector<double>& p, size_t i) {
    return expected_estimate(coherency(p[0]), coherency(p[1]), p[2], floor, r[i]);
  };
  auto angle = [](double c) { return coherency_angle(std::sqrt(std::max(c, 0.0))); };
  return fit_nonlinear(measured, model, {angle(measured.front()), angle(measured.back()), 1 / r.back()},
                       {"g0_angle", "g_far_angle", "inverse_length"});
}

// The jackknife standard error of each parameter: sqrt((G - 1)/G sum_g (p_g - mean p)^2).
std::vector<double> jackknife_errors(const std::vector<std::vector<double>>& leave_one_out)
{
  const double groups = double(leave_one_out.size());
  std::vector<double> errors;
  for (size_t p = 0; p < leave_one_out.front().size(); ++p) {
    double mean = 0, spread = 0;
    for (const auto& g : leave_one_out) mean += g[p] / groups;
    for (const auto& g : leave_one_out) spread += (g[p] - mean) * (g[p] - mean);
    errors.push_back(std::sqrt((groups - 1) / groups * spread));
  }
  return errors;
}

}  // namespace

CoherenceFit fit_coherence(const CoherenceByDistance& coherence)
{
  const auto& r = coherence.distance;
  if (r.size() < kFitDistances)
    throw AnalysisError("the coherence fit needs " + std::to_string(kFitDistances) + " distances, got " +
                        std::to_string(r.size()));
  if (coherence.without_group.size() < 3)
    throw AnalysisError("the coherence fit's jackknife needs 3 groups of segments, got " +
                        std::to_string(coherence.without_group.size()) + ": analyse a longer window");
  CoherenceFit fit;
  fit.raw = fit_decay(r, coherence.coherence, coherence.noise_floor);
  // The distances share the same segments, so the fit's residuals are correlated and its own
  // errors far too small: the errors are the jackknife's over the groups of segments.
  const double groups = double(coherence.without_group.size());
  auto parameters = [](const FitResult& f) {  // coherencies squared: coherences
    const double g0 = coherency(f["g0_angle"].value), g_far = coherency(f["g_far_angle"].value);
    return std::vector<double>{g0 * g0, g_far * g_far, f["inverse_length"].value};
  };
  std::vector<std::vector<double>> leave_one_out;
  for (const auto& curve : coherence.without_group)
    leave_one_out.push_back(parameters(fit_decay(r, curve, coherence.noise_floor * groups / (groups - 1))));
  const auto errors = jackknife_errors(leave_one_out);
  const auto values = parameters(fit.raw);
  fit.short_range = Estimate{values[0], errors[0]};
  fit.plateau = Estimate{values[1], errors[1]};
  fit.inverse_length = Estimate{values[2], errors[2]};
  fit.g0 = coherency(fit.raw["g0_angle"].value);
  fit.g_far = coherency(fit.raw["g_far_angle"].value);
  const double kappa = values[2];
  if (kappa > 2 * errors[2] && coherence_decays(coherence))
    fit.length = Estimate{1 / kappa, errors[2] / (kappa * kappa)};
  return fit;
}

Estimate coherence_decay(const CoherenceByDistance& coherence)
{
  if (coherence.without_group.size() < 2 || coherence.coherence.empty())
    throw AnalysisError("the coherence's decay needs 2 groups of segments and a distance");
  auto decay = [](const std::vector<double>& c) { return c.front() - c.back(); };
  std::vector<std::vector<double>> leave_one_out;
  for (const auto& curve : coherence.without_group) leave_one_out.push_back({decay(curve)});
  return Estimate{decay(coherence.coherence), jackknife_errors(leave_one_out).front()};
}

bool coherence_decays(const CoherenceByDistance& coherence)
{
  const auto decay = coherence_decay(coherence);
  return decay.value > 2 * decay.error.value_or(0) && decay.value > coherence.noise_floor;
}

namespace {

// The share of m = 0 in the band's power, and the sign-resolved |m| >= 1 with most power with
// its balance (the x-Nyquist bin of an even column count, m = +-M/2, has no direction).
void judge_wavenumbers(const std::vector<double>& band_power, int columns, double averages, PatternVerdict& verdict)
{
  const int lowest_m = -(columns / 2), highest_m = columns / 2;
  const bool shared_nyquist = columns % 2 == 0;
  if (band_power.size() != static_cast<size_t>(highest_m - lowest_m + 1))
    throw AnalysisError("the band power has " + std::to_string(band_power.size()) + " wavenumbers, not " +
                        std::to_string(highest_m - lowest_m + 1) + " for " + std::to_string(columns) + " columns");
  auto power = [&](int m) { return band_power[static_cast<size_t>(m - lowest_m)]; };
  double total = 0;
  for (int m = shared_nyquist ? lowest_m + 1 : lowest_m; m <= highest_m; ++m) total += power(m);
  verdict.uniform_fraction = total > 0 ? power(0) / total : 0;
  double best = -1;
  for (int m = 1; m <= (shared_nyquist ? highest_m - 1 : highest_m); ++m)
    if (power(m) + power(-m) > best) {
      best = power(m) + power(-m);
      const double plus = power(m), minus = power(-m), b = (plus - minus) / (plus + minus);
      verdict.dominant_m = plus >= minus ? m : -m;
      verdict.balance = Estimate{b, (1 - b * b) / std::sqrt(2 * averages)};
    }
}

bool one_direction_dominates(const Estimate& balance)
{
  return std::abs(balance.value) >= kTravellingBalance && std::abs(balance.value) > 2 * balance.error.value_or(0);
}

// "m = 0 holds X % of the power at f; |m| = k (wavelength W d): balance B" (the numbers of every verdict).
std::string wavenumber_text(const PatternVerdict& verdict, double cell_length_d)
{
  std::string text = "m = 0 holds " + number(100 * verdict.uniform_fraction) + " % of the power at f";
  if (verdict.dominant_m == 0) return text;
  const int m = std::abs(verdict.dominant_m);
  const auto& b = verdict.balance;
  return text + "; of the other wavenumbers |m| = " + std::to_string(m) + " (wavelength " + number(cell_length_d / m) +
         " d) holds most, balance (P(+m) - P(-m)) / (P(+m) + P(-m)) = " + format_estimate(b.value, b.error);
}

}  // namespace

PatternVerdict judge_pattern(const std::vector<double>& band_power, int columns, const CoherenceByDistance& coherence,
                             const std::optional<CoherenceFit>& fit, double cell_length_d)
{
  PatternVerdict verdict;
  judge_wavenumbers(band_power, columns, coherence.averages, verdict);
  const std::string far = "coherence " + number(coherence.coherence.back()) +
                          " at r = " + number(coherence.distance.back()) + " d (noise floor " +
                          number(coherence.noise_floor) + ")";
  std::string headline;
  const bool resolved = coherence.averages >= kLeastAverages;
  const double neighbours = coherence.coherence.front();
  if (resolved && neighbours < kIncoherentNeighbours * coherence.noise_floor) {
    verdict.pattern = OscillationPattern::Local;
    headline = "local: neighbouring columns no more coherent than incoherent ones (" + number(neighbours) +
               " at r = " + number(coherence.distance.front()) + " d, below twice the noise floor " +
               number(coherence.noise_floor) + "): coherence length below one column width";
  } else if (resolved && fit && fit->length &&
             fit->length->value + 2 * fit->length->error.value_or(0) < cell_length_d / 2 &&
             fit->plateau.value < kCoherentPlateau * coherence.coherence.front()) {
    verdict.pattern = OscillationPattern::Local;
    headline = "local: coherence length " + format_estimate(fit->length->value, fit->length->error) +
               " d, shorter than half the cell (" + number(cell_length_d / 2) +
               " d) by more than twice its error, the coherence falling from " +
               format_estimate(fit->short_range.value, fit->short_range.error) + " to a plateau of " +
               format_estimate(fit->plateau.value, fit->plateau.error);
  } else if (verdict.uniform_fraction >= kUniformFraction) {
    verdict.pattern = OscillationPattern::Uniform;
    headline = "uniform across the cell";
  } else if (one_direction_dominates(verdict.balance)) {
    verdict.pattern = OscillationPattern::Travelling;
    headline = std::string("travelling along ") + (verdict.dominant_m > 0 ? "+x" : "-x");
  } else {
    verdict.pattern = OscillationPattern::Standing;
    headline = "standing";
  }
  verdict.text = headline + "; " + wavenumber_text(verdict, cell_length_d) + "; " + far;
  if (!resolved)
    verdict.text += "; the coherence does not resolve where the oscillation lives: " + number(coherence.averages) +
                    " averages (fewer than " + number(kLeastAverages) +
                    "), so incoherent columns could read as much (analyse a longer window)";
  else if (verdict.pattern != OscillationPattern::Local && coherence.without_group.size() >= 2 &&
           !coherence_decays(coherence)) {
    const auto decay = coherence_decay(coherence);
    verdict.text +=
        "; no coherence length: the coherence does not decay over the cell (" + number(coherence.coherence.front()) +
        " at r = " + number(coherence.distance.front()) + " d, less by " + format_estimate(decay.value, decay.error) +
        " at r = " + number(coherence.distance.back()) + " d: not beyond twice its error and the noise floor)";
  }
  return verdict;
}

namespace {

void add_results(const AlongCell& along, ResultTable& results)
{
  const auto& c = along.coherence;
  const auto& v = along.verdict;
  const double width = along.spectrum.cell_length / along.spectrum.columns;
  results.add("columns", along.spectrum.columns, "", "columns of v(x, t) tiling the cell (columns.chunk)");
  results.add("column_width", width, "d", "width of a column");
  results.add("coherence_band", static_cast<double>(c.band.size()) * along.spectrum.resolution_hz, "Hz",
              "band at the peak f (f +- its half width) over which cross spectra and wavenumber power are summed");
  results.add("coherence_averages", c.averages, "",
              "effective independent averages per cross spectrum (segments x band bins, Hann-correlated)");
  results.add("coherence_floor", c.noise_floor, "", "expected coherence of incoherent columns, 1 / averages");
  results.add("coherence_far", c.coherence.back(), "",
              "coherence of v at f between columns " + number(c.distance.back()) + " d apart (the largest distance)");
  if (along.decay)
    results.add("coherence_decay", *along.decay, "",
                "coherence at the first distance minus at the last: xi is given only when it exceeds twice its error "
                "and the noise floor");
  if (along.fit) {
    results.add("coherence_short_range", along.fit->short_range, "",
                "c0 = g0^2 of the fit C(r) = (g_far + (g0 - g_far) exp(-r / xi))^2, the coherence at r -> 0");
    results.add("coherence_plateau", along.fit->plateau, "",
                "g_far^2 of the same fit: the coherence left across the cell");
    results.add("coherence_inverse_length", along.fit->inverse_length, "1/d", "1/xi of the coherence fit");
    if (along.fit->length)
      results.add("coherence_length", *along.fit->length, "d", "xi: the correlation of v at f decays as exp(-r/xi)");
  }
  results.add("wavenumber_uniform_fraction", v.uniform_fraction, "", "share of the power at f at m = 0");
  if (v.dominant_m != 0) {
    results.add("wavenumber_dominant_m", v.dominant_m, "",
                "|m| >= 1 with most power at f, k = 2 pi m / L, signed by its stronger direction (+: along +x)");
    results.add("wavenumber_balance", v.balance, "", "(P(+m) - P(-m)) / (P(+m) + P(-m)) at the dominant |m|");
  }
  if (along.phase_velocity)
    results.add("phase_velocity", *along.phase_velocity, "sqrt(g d)", "f L / m of the travelling wave (+: along +x)");
  results.add("oscillation_pattern", static_cast<int>(v.pattern), "",
              "1 uniform, 2 standing, 3 travelling, 4 local: " + pattern_name(v.pattern));
}

}  // namespace

AlongCell analyse_along_cell(const SpaceTimeField& field, const SpectralPeak& peak, const SpectrumOptions& options,
                             double reduced_rate_hz, ResultTable& results, std::vector<std::string>& warnings)
{
  AlongCell along;
  along.frequency_hz = peak.frequency_hz;
  along.spectrum = space_time_spectrum(field, options);
  along.coherence = coherence_by_distance(field, options, peak.frequency_hz, peak.frequency_error_hz);
  along.band_power = band_power_by_m(along.spectrum, along.coherence.band);
  // A window of fewer than 3 segments has no jackknife: the report says so, as it says when the
  // coherence does not decay; a fit that fails on enough data is a warning.
  if (along.coherence.without_group.size() < 3) {
    along.no_fit_reason = "no coherence length: the window holds " + std::to_string(along.coherence.segments) +
                          " segment(s), its error (a jackknife) needs 3";
  } else {
    along.decay = coherence_decay(along.coherence);
    if (along.coherence.distance.size() >= kFitDistances && !coherence_decays(along.coherence))
      along.no_fit_reason = "no coherence length: the coherence does not decay over the cell";
    else try {
        along.fit = fit_coherence(along.coherence);
      } catch (const AnalysisError& e) {
        along.no_fit_reason = "coherence length not fitted: " + std::string(e.what());
        warnings.push_back(along.no_fit_reason);
      }
  }
  along.verdict =
      judge_pattern(along.band_power, along.spectrum.columns, along.coherence, along.fit, field.cell_length);
  if (along.verdict.pattern == OscillationPattern::Travelling) {
    const double speed = peak.frequency_hz * field.cell_length / along.verdict.dominant_m / reduced_rate_hz;
    along.phase_velocity = Estimate{speed, std::abs(speed) * peak.frequency_error_hz / peak.frequency_hz};
  }
  add_results(along, results);
  return along;
}

}  // namespace cdpost
