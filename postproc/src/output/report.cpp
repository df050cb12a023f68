#include "output/report.h"

namespace cdpost {

MarkdownReport::MarkdownReport(const std::string& title)
{
  text_ << "# " << title << "\n\n";
}

void MarkdownReport::heading(const std::string& text)
{
  text_ << "## " << text << "\n\n";
}

void MarkdownReport::paragraph(const std::string& text)
{
  text_ << text << "\n\n";
}

void MarkdownReport::table(const ResultTable& results)
{
  text_ << results.markdown() << "\n";
}

void MarkdownReport::table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows)
{
  auto row_text = [](const std::vector<std::string>& cells) {
    std::string line = "|";
    for (const auto& cell : cells) line += " " + cell + " |";
    return line + "\n";
  };
  text_ << row_text(header) << row_text(std::vector<std::string>(header.size(), "---"));
  for (const auto& row : rows) text_ << row_text(row);
  text_ << "\n";
}

void MarkdownReport::figure(const std::string& figures_dir, const std::string& name, const std::string& caption)
{
  const std::string stem = figures_dir + "/" + name;
  text_ << "![" << caption << "](" << stem << ".png)\n\n*" << caption << "* ([SVG](" << stem << ".svg))\n\n";
}

void MarkdownReport::warnings(const std::vector<std::string>& warnings)
{
  if (warnings.empty()) return;
  heading("Warnings");
  for (const auto& w : warnings) text_ << "- " << w << "\n";
  text_ << "\n";
}

void MarkdownReport::write(const std::string& path) const
{
  open_output(path) << text_.str();
}

}  // namespace cdpost
