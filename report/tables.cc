#include "tables.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <sstream>
#include <string>
#include <utility>

namespace fibrecheck {

namespace {

/// U+2009, the space between groups of digits.
constexpr const char* kThinSpace = "\u2009";

}  // namespace

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

std::string count(long value) {
  const std::string digits = std::to_string(value);
  if (value < 10000) return digits;
  std::string out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += kThinSpace;
    out += digits[i];
  }
  return out;
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
      {"°", "\\ensuremath{^\\circ}"}, {kThinSpace, "\\,"}};
  for (const auto& [utf8, latex] : symbols) {
    const std::size_t length = std::char_traits<char>::length(utf8);
    if (text.compare(i, length, utf8) == 0) {
      i += length - 1;
      return latex;
    }
  }
  return nullptr;
}

bool is_word_character(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.';
}

/// The length of the number in scientific notation ("4.85e-08", "-1e+03") that starts at
/// text[i] and stands as a word of its own, or 0; its mantissa's length in `mantissa`.
std::size_t scientific_number_at(const std::string& text, std::size_t i, std::size_t& mantissa) {
  if (i > 0 && (is_word_character(text[i - 1]) || text[i - 1] == '-')) return 0;
  std::size_t j = i;
  if (j < text.size() && (text[j] == '-' || text[j] == '+')) ++j;
  const std::size_t digits = j;
  while (j < text.size() && std::isdigit(static_cast<unsigned char>(text[j]))) ++j;
  if (j == digits) return 0;
  if (j < text.size() && text[j] == '.') {
    ++j;
    while (j < text.size() && std::isdigit(static_cast<unsigned char>(text[j]))) ++j;
  }
  mantissa = j - i;
  if (j >= text.size() || text[j] != 'e') return 0;
  ++j;
  if (j < text.size() && (text[j] == '-' || text[j] == '+')) ++j;
  const std::size_t exponent = j;
  while (j < text.size() && std::isdigit(static_cast<unsigned char>(text[j]))) ++j;
  if (j == exponent) return 0;
  if (j < text.size() && (std::isalpha(static_cast<unsigned char>(text[j])) || text[j] == '_'))
    return 0;
  return j - i;
}

/// "4.85e-08" as $4.85\times10^{-8}$ (a zero as 0).
std::string typeset_scientific(const std::string& number, std::size_t mantissa) {
  const std::string m = number.substr(0, mantissa);
  const int exponent = std::stoi(number.substr(mantissa + 1));
  if (std::stod(m) == 0.0) return "0";
  if (exponent == 0) return m;
  return "\\ensuremath{" + m + "\\times10^{" + std::to_string(exponent) + "}}";
}

}  // namespace

std::string latex_escape(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    std::size_t mantissa = 0;
    if (const std::size_t length = scientific_number_at(text, i, mantissa)) {
      out += typeset_scientific(text.substr(i, length), mantissa);
      i += length - 1;
      continue;
    }
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


namespace {

/// Whether a table cell is a number (or "–" for none): such columns are set flush right.
bool is_numeric_cell(const std::string& text) {
  if (text.empty() || text == "–" || text == "-") return true;
  std::string cell = text;
  for (std::size_t at; (at = cell.find(kThinSpace)) != std::string::npos;)
    cell.erase(at, std::char_traits<char>::length(kThinSpace));
  char* end = nullptr;
  std::strtod(cell.c_str(), &end);
  if (end == cell.c_str()) return false;
  const std::string rest(end);
  return rest.empty() || rest == "%" || rest == "×";
}

bool is_numeric_column(const Table& t, std::size_t column) {
  for (const auto& row : t.rows)
    if (column < row.size() && !is_numeric_cell(row[column])) return false;
  return true;
}

}  // namespace

std::string latex_text(const std::string& text) {
  std::string out;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t math = text.find('$', at), cite = text.find("[@", at),
                      ref = text.find("[#", at);
    const std::size_t next = std::min({math, cite, ref});
    out += latex_escape(text.substr(at, next - at));
    if (next == std::string::npos) break;
    const std::size_t end = next == math ? text.find('$', math + 1) : text.find(']', next);
    if (end == std::string::npos) {
      out += latex_escape(text.substr(next));
      break;
    }
    const std::string inside = text.substr(next + 2, end - next - 2);
    if (next == math)
      out += text.substr(math, end + 1 - math);
    else if (next == cite)
      out += "\\cite{" + inside + "}";
    else
      out += (inside.rfind("fig:", 0) == 0 ? "Figure~\\ref{" : "Table~\\ref{") + inside + "}";
    at = end + 1;
  }
  return out;
}

std::string markdown(const Table& t, int number) {
  std::ostringstream out;
  out << "**Table " << number << ".** " << t.caption << "\n\n|";
  for (const std::string& h : t.header) out << " " << h << " |";
  out << "\n|";
  for (std::size_t i = 0; i < t.header.size(); ++i)
    out << (is_numeric_column(t, i) ? " ---: |" : " --- |");
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
  out << "\\begin{table}[htbp]\n  \\centering\n  \\caption{" << latex_text(t.caption)
      << "}\n  \\label{tab:" << t.label
      // A caption above a table has no space below it of its own: the top rule would touch it.
      << "}\n  \\vspace{0.6ex}\n  \\begin{adjustbox}{max width=\\linewidth}\n  \\begin{tabular}{";
  for (std::size_t i = 0; i < t.header.size(); ++i) out << (is_numeric_column(t, i) ? "r" : "l");
  out << "}\n    \\toprule\n    ";
  for (std::size_t i = 0; i < t.header.size(); ++i)
    out << (i ? " & " : "") << latex_escape(t.header[i]);
  out << " \\\\\n    \\midrule\n";
  for (const auto& row : t.rows) {
    out << "    ";
    for (std::size_t i = 0; i < row.size(); ++i) out << (i ? " & " : "") << latex_escape(row[i]);
    out << " \\\\\n";
  }
  out << "    \\bottomrule\n  \\end{tabular}\n  \\end{adjustbox}\n\\end{table}\n";
  return out.str();
}

}  // namespace fibrecheck
