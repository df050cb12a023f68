#include "analysis/series_comparison.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace cdpost {

std::array<std::string, 2> default_labels(const std::string& manifest, const std::string& other)
{
  const std::filesystem::path first(manifest), second(other);
  const auto folder = [](const std::filesystem::path& p) { return std::filesystem::absolute(p).parent_path(); };
  if (folder(first) != folder(second)) return {folder(first).filename().string(), folder(second).filename().string()};
  return {first.stem().string(), second.stem().string()};
}

SeriesComparison compare_series(const SeriesSettings& settings, const std::string& other,
                                const std::array<std::string, 2>& labels)
{
  read_manifest(other);
  SeriesSettings second = settings;
  second.manifest = other;
  return {{analyse_series(settings), analyse_series(second)}, labels};
}

std::vector<ComparedFit> compared_fits(const SeriesComparison& comparison)
{
  std::vector<ComparedFit> fits;
  for (size_t s = 0; s < 2; ++s)
    for (const auto& row : comparison.series[s].fits.rows()) {
      auto found = std::find_if(fits.begin(), fits.end(), [&](const ComparedFit& f) { return f.name == row.name; });
      if (found == fits.end()) found = fits.insert(fits.end(), ComparedFit{row.name, row.unit, {}, std::nullopt});
      found->estimates[s] = Estimate{row.value, row.error};
    }
  for (auto& fit : fits) {
    const auto &a = fit.estimates[0], &b = fit.estimates[1];
    if (a && b && a->error && b->error && (*a->error > 0 || *b->error > 0))
      fit.difference_sigma = (b->value - a->value) / std::hypot(*a->error, *b->error);
  }
  return fits;
}

std::vector<std::string> comparison_warnings(const SeriesComparison& comparison)
{
  std::vector<std::string> warnings;
  for (size_t s = 0; s < 2; ++s)
    for (const auto& w : comparison.series[s].warnings) warnings.push_back(comparison.labels[s] + ": " + w);
  return warnings;
}

}  // namespace cdpost
