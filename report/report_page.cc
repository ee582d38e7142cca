#include "report_page.h"

#include "atomic_file.h"
#include "csv_file.h"

namespace fibrecheck {

namespace {

/// The works the report cites, as "[@key]" in its texts.
struct Reference {
  const char* key;
  const char* short_form;  ///< where the Markdown cites it
  const char* plain;       ///< the Markdown's list of references
  const char* entry;       ///< the bibliography's, in LaTeX
};
constexpr Reference kReferences[] = {
    {"sherburn2007", "Sherburn 2007",
     "M. Sherburn. Geometric and Mechanical Modelling of Textiles. PhD thesis, University of "
     "Nottingham, 2007. Chapter 4.",
     "M.~Sherburn. \\emph{Geometric and Mechanical Modelling of Textiles}. PhD thesis, "
     "University of Nottingham, 2007. Chapter~4."},
    {"vanwyk1946", "van Wyk 1946",
     "C. M. van Wyk. Note on the compressibility of wool. Journal of the Textile Institute, "
     "37:T285-T292, 1946.",
     "C.~M. van Wyk. Note on the compressibility of wool. \\emph{Journal of the Textile "
     "Institute}, 37:T285--T292, 1946."},
    {"toll1998", "Toll 1998",
     "S. Toll. Packing mechanics of fiber reinforcements. Polymer Engineering and Science, "
     "38(8):1337-1350, 1998.",
     "S.~Toll. Packing mechanics of fiber reinforcements. \\emph{Polymer Engineering and "
     "Science}, 38(8):1337--1350, 1998."}};

const Reference* reference(const std::string& key) {
  for (const Reference& r : kReferences)
    if (key == r.key) return &r;
  return nullptr;
}

/// The same text as Markdown: mathematics kept between dollars, citations as (Author Year).
std::string markdown_text(const std::string& text) {
  std::string out;
  std::size_t at = 0;
  for (std::size_t cite = text.find("[@"); cite != std::string::npos;
       cite = text.find("[@", at)) {
    const std::size_t end = text.find(']', cite);
    if (end == std::string::npos) break;
    const Reference* r = reference(text.substr(cite + 2, end - cite - 2));
    out += text.substr(at, cite - at) + "(" + (r ? r->short_form : "?") + ")";
    at = end + 1;
  }
  return out + text.substr(at);
}

}  // namespace

ReportPage::ReportPage(const std::string& folder)
    : folder_(folder), gnuplot_((folder_ / "figures").string()) {
  std::filesystem::create_directories(folder_ / "tables");
  std::filesystem::create_directories(folder_ / "figures");
  std::filesystem::create_directories(folder_ / "data");
}

void ReportPage::section(const std::string& title, const std::string& text) {
  md_ << "\n## " << title << "\n\n" << markdown_text(text) << "\n";
  tex_ << "\n\\section{" << latex_escape(title) << "}\n" << latex_text(text) << "\n";
}

void ReportPage::table(const Table& t) {
  ++summary_.tables;
  numbers_.emplace_back("tab:" + t.label, "Table " + std::to_string(summary_.tables));
  md_ << "\n" << markdown(t, summary_.tables) << "\n";
  write_file_atomically((folder_ / "tables" / (t.label + ".tex")).string(), latex(t));
  tex_ << "\n\\input{tables/" << t.label << ".tex}\n";
}

void ReportPage::finding(const std::string& text) { findings_.push_back(text); }

void ReportPage::appendix_table(const std::string& appendix_title, const Table& t) {
  write_file_atomically((folder_ / "tables" / (t.label + ".tex")).string(), latex(t));
  appendix_.emplace_back(appendix_title, t);
}

void ReportPage::figure(const std::string& name, const std::string& caption,
                        const std::string& body, const std::vector<Gnuplot::Series>& series) {
  std::string why;
  if (!gnuplot_.plot(name, body, series, &why)) {
    summary_.missing.push_back(name + ": " + why);
    return;
  }
  ++summary_.figures;
  numbers_.emplace_back("fig:" + name, "Figure " + std::to_string(summary_.figures));
  md_ << "\n![Figure " << summary_.figures << "](figures/" << name << ".png)\n\n**Figure "
      << summary_.figures << ".** " << markdown_text(caption) << "\n";
  tex_ << "\n\\begin{figure}[htbp]\n  \\centering\n  "
          "\\includegraphics[width=0.85\\linewidth]{figures/"
       << name << "}\n  \\caption{" << latex_text(caption) << "}\n  \\label{fig:" << name
       << "}\n\\end{figure}\n";
}

void ReportPage::csv(const std::string& name, const std::vector<std::string>& header,
                     const std::vector<std::vector<std::string>>& rows) {
  write_csv((folder_ / "data" / (name + ".csv")).string(), header, rows);
}

// The opening paragraphs: what is checked, against what, and how the errors are measured.
const char* const kIntroduction =
    "This report checks the iterative method of [@sherburn2007] for the compaction of fibre tows "
    "(called the seed's method below, its equations cited by their numbers there): fibres are "
    "simply supported Euler-Bernoulli beams, contact forces are found by the repeated correction "
    "$P' = P + c\\,d$ measured on the displaced fibres, line contacts between nearly parallel "
    "fibres are cut into cross-section slices, and a run stops on an overlap or strain-energy "
    "criterion. Every number is checked against an implicit finite-element reference of the same "
    "physics that solves all contacts at once.\n\n"
    "Errors are relative and the worst over the scene (docs/formats.md): deflection, max over "
    "fibres and samples of $\\|u - u_\\mathrm{truth}\\| / \\max\\|u_\\mathrm{truth}\\|$; force, "
    "max over contact pairs of the relative error of the total force; energy, of "
    "$\\tfrac12\\sum P\\,v$. The ground truth is the implicit finite-element reference with "
    "continuous line contact (on slices where a scene has only point contacts).\n";

std::string ReportPage::with_numbers(std::string markdown) const {
  for (const auto& [label, number] : numbers_) {
    const std::string mark = "[#" + label + "]";
    for (std::size_t at = markdown.find(mark); at != std::string::npos;
         at = markdown.find(mark, at + number.size()))
      markdown.replace(at, mark.size(), number);
  }
  return markdown;
}

ReportSummary ReportPage::finish(const std::vector<std::string>& sources) {
  std::ostringstream appendix_md, appendix_tex;
  for (const auto& [title, t] : appendix_) {
    ++summary_.tables;
    numbers_.emplace_back("tab:" + t.label, "Table " + std::to_string(summary_.tables));
    appendix_md << "\n## " << title << "\n\n" << markdown(t, summary_.tables) << "\n";
    appendix_tex << "\n\\section{" << latex_escape(title) << "}\n\\input{tables/" << t.label
                 << ".tex}\n";
  }
  std::ostringstream md;
  md << "# fibrecheck: the iterative fibre-contact method, checked\n\n"
     << markdown_text(kIntroduction);
  if (!findings_.empty()) {
    md << "\n## Key findings\n\n";
    for (const std::string& f : findings_) md << "- " << markdown_text(f) << "\n";
  }
  md << md_.str() << "\n## References\n\n";
  for (const Reference& r : kReferences) md << "- " << r.plain << "\n";
  if (!appendix_.empty()) md << "\n# Appendix\n" << appendix_md.str();
  md << "\n---\nData read: " << sources.size() << " files; "
     << "tables in `tables/`, figures in `figures/` (their gnuplot scripts in `figures/src/`), "
        "the numbers in `data/`.\n";
  if (!summary_.missing.empty()) {
    md << "\nFigures not drawn:\n";
    for (const std::string& m : summary_.missing) md << "- " << m << "\n";
  }
  write_file_atomically((folder_ / "report.md").string(), with_numbers(md.str()));
  std::ostringstream tex;
  tex << "\\documentclass[a4paper,11pt]{article}\n\\usepackage[T1]{fontenc}\n"
         "\\usepackage{lmodern}\n\\usepackage{amsmath}\n\\usepackage{booktabs}\n"
         "\\usepackage{graphicx}\n\\usepackage{adjustbox}\n\\usepackage[section]{placeins}\n"
         "\\usepackage[margin=2.2cm]{geometry}\n"
         // gnuplot's PDFs each carry a page group; pdfTeX warns once per page that has two.
         "\\ifdefined\\pdfsuppresswarningpagegroup\\pdfsuppresswarningpagegroup=1\\fi\n"
         "\\title{fibrecheck: the iterative fibre-contact method, checked}\n\\author{}\n"
         "\\date{}\n"
         "\\begin{document}\n\\maketitle\n"
      << latex_text(kIntroduction) << "\n";
  if (!findings_.empty()) {
    tex << "\n\\section*{Key findings}\n\\begin{itemize}\n";
    for (const std::string& f : findings_) tex << "\\item " << latex_text(f) << "\n";
    tex << "\\end{itemize}\n";
  }
  tex << tex_.str() << "\n\\begin{thebibliography}{9}\n";
  for (const Reference& r : kReferences) tex << "\\bibitem{" << r.key << "} " << r.entry << "\n";
  tex << "\\end{thebibliography}\n";
  if (!appendix_.empty()) tex << "\n\\appendix\n" << appendix_tex.str();
  tex << "\\end{document}\n";
  write_file_atomically((folder_ / "report.tex").string(), tex.str());
  return summary_;
}

}  // namespace fibrecheck
