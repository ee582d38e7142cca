#include "tables.h"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <utility>

namespace fibrecheck {

std::string sci(double value) {
  if (!std::isfinite(value)) return "–";
  char text[32];
  std::snprintf(text, sizeof text, "%.2e", value);
  return text;
}

std::string seconds(double value) {
  if (!std::isfinite(value)) return "–";
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

std::string fixed3(double value) {
  if (!std::isfinite(value)) return "–";
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(3);
  out << value;
  return out.str();
}

namespace {

/// The LaTeX of the UTF-8 symbol that starts at text[i], advancing i to its last byte; null for
/// anything else.
const char* latex_of_symbol(const std::string& text, std::size_t& i) {
  static const std::pair<const char*, const char*> symbols[] = {
      {"–", "--"},           {"−", "\\ensuremath{-}"},   {"×", "\\ensuremath{\\times}"},
      {"≤", "\\ensuremath{\\le}"}, {"≥", "\\ensuremath{\\ge}"},  {"≈", "\\ensuremath{\\approx}"},
      {"∝", "\\ensuremath{\\propto}"}, {"λ", "\\ensuremath{\\lambda}"},
      {"μ", "\\ensuremath{\\mu}"},   {"µ", "\\ensuremath{\\mu}"},   {"Σ", "\\ensuremath{\\Sigma}"},
      {"½", "\\ensuremath{\\tfrac{1}{2}}"}, {"‖", "\\ensuremath{\\|}"}, {"·", "\\ensuremath{\\cdot}"},
      {"ⁿ", "\\ensuremath{^{n}}"}, {"²", "\\ensuremath{^{2}}"}, {"³", "\\ensuremath{^{3}}"},
      {"§", "\\S{}"},          {"…", "\\dots{}"},          {"→", "\\ensuremath{\\to}"},
      {"°", "\\ensuremath{^\\circ}"}};
  for (const auto& [utf8, latex] : symbols) {
    const std::size_t length = std::char_traits<char>::length(utf8);
    if (text.compare(i, length, utf8) == 0) {
      i += length - 1;
      return latex;
    }
  }
  return nullptr;
}

}  // namespace

std::string latex_escape(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    switch (c) {
      case '_':
        out += "\\_";
        break;
      case '%':
        out += "\\%";
        break;
      case '&':
        out += "\\&";
        break;
      case '#':
        out += "\\#";
        break;
      case '$':
        out += "\\$";
        break;
      case '{':
        out += "\\{";
        break;
      case '}':
        out += "\\}";
        break;
      case '^':
        out += "\\^{}";
        break;
      case '~':
        out += "\\~{}";
        break;
      case '\\':
        out += "\\textbackslash{}";
        break;
      default:
        // The UTF-8 symbols of the report's texts, as LaTeX.
        if (const char* latex = latex_of_symbol(text, i)) {
          out += latex;
        } else {
          out += c;
        }
    }
  }
  return out;
}

std::string markdown(const Table& t, int number) {
  std::ostringstream out;
  out << "**Table " << number << ".** " << t.caption << "\n\n|";
  for (const std::string& h : t.header) out << " " << h << " |";
  out << "\n|";
  for (std::size_t i = 0; i < t.header.size(); ++i) out << (i == 0 ? " --- |" : " ---: |");
  out << "\n";
  for (const auto& row : t.rows) {
    out << "|";
    for (const std::string& c : row) out << " " << c << " |";
    out << "\n";
  }
  return out.str();
}

std::string latex(const Table& t) {
  std::ostringstream out;
  out << "\\begin{table}[htbp]\n  \\centering\n  \\caption{" << latex_escape(t.caption)
      << "}\n  \\label{tab:" << t.label << "}\n  \\begin{tabular}{l";
  for (std::size_t i = 1; i < t.header.size(); ++i) out << "r";
  out << "}\n    \\toprule\n    ";
  for (std::size_t i = 0; i < t.header.size(); ++i)
    out << (i ? " & " : "") << latex_escape(t.header[i]);
  out << " \\\\\n    \\midrule\n";
  for (const auto& row : t.rows) {
    out << "    ";
    for (std::size_t i = 0; i < row.size(); ++i) out << (i ? " & " : "") << latex_escape(row[i]);
    out << " \\\\\n";
  }
  out << "    \\bottomrule\n  \\end{tabular}\n\\end{table}\n";
  return out.str();
}

}  // namespace fibrecheck
