#include "tables.h"

#include <cmath>
#include <cstdio>
#include <sstream>

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
        // A few UTF-8 symbols the captions use, as LaTeX.
        if (text.compare(i, 3, "–") == 0) {
          out += "--";
          i += 2;
        } else if (text.compare(i, 2, "×") == 0) {
          out += "$\\times$";
          i += 1;
        } else if (text.compare(i, 2, "≤") == 0 || text.compare(i, 3, "≤") == 0) {
          out += "$\\le$";
          i += text.compare(i, 3, "≤") == 0 ? 2 : 1;
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
