// Markdown reports: headings, text, result tables and embedded figures.
#pragma once

#include <sstream>
#include <string>
#include <vector>

#include "output/results.h"

namespace cdpost {

class MarkdownReport {
 public:
  explicit MarkdownReport(const std::string& title);
  void heading(const std::string& text);
  void paragraph(const std::string& text);
  void table(const ResultTable& results);
  // A table of text cells, one row per entry of `rows`, each as long as `header`.
  void table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows);
  // Embeds FIGURES_DIR/NAME.png, links the SVG.
  void figure(const std::string& figures_dir, const std::string& name, const std::string& caption);
  void warnings(const std::vector<std::string>& warnings);
  void write(const std::string& path) const;

 private:
  std::ostringstream text_;
};

}  // namespace cdpost
