#include "report_page.h"

#include "atomic_file.h"
#include "csv_file.h"

namespace fibrecheck {

ReportPage::ReportPage(const std::string& folder)
    : folder_(folder), gnuplot_((folder_ / "figures").string()) {
  std::filesystem::create_directories(folder_ / "tables");
  std::filesystem::create_directories(folder_ / "figures");
  std::filesystem::create_directories(folder_ / "data");
}

void ReportPage::section(const std::string& title, const std::string& text) {
  md_ << "\n## " << title << "\n\n" << text << "\n";
  tex_ << "\n\\section{" << latex_escape(title) << "}\n" << latex_escape(text) << "\n";
}

void ReportPage::table(const Table& t) {
  ++summary_.tables;
  md_ << "\n" << markdown(t, summary_.tables) << "\n";
  write_file_atomically((folder_ / "tables" / (t.label + ".tex")).string(), latex(t));
  tex_ << "\n\\input{tables/" << t.label << ".tex}\n";
}

void ReportPage::figure(const std::string& name, const std::string& caption,
                        const std::string& body, const std::vector<Gnuplot::Series>& series) {
  std::string why;
  if (!gnuplot_.plot(name, body, series, &why)) {
    summary_.missing.push_back(name + ": " + why);
    return;
  }
  ++summary_.figures;
  md_ << "\n![Figure " << summary_.figures << "](figures/" << name << ".png)\n\n**Figure "
      << summary_.figures << ".** " << caption << "\n";
  tex_ << "\n\\begin{figure}[htbp]\n  \\centering\n  "
          "\\includegraphics[width=0.85\\linewidth]{figures/"
       << name << ".png}\n  \\caption{" << latex_escape(caption) << "}\n  \\label{fig:" << name
       << "}\n\\end{figure}\n";
}

void ReportPage::csv(const std::string& name, const std::vector<std::string>& header,
                     const std::vector<std::vector<std::string>>& rows) {
  write_csv((folder_ / "data" / (name + ".csv")).string(), header, rows);
}

ReportSummary ReportPage::finish(const std::vector<std::string>& sources) {
  std::ostringstream md;
  md << "# fibrecheck: the iterative fibre-contact method, checked\n\n"
     << "Errors are relative and the worst over the scene (docs/formats.md): deflection, max over "
        "fibres and samples of ‖u − u_truth‖ / max‖u_truth‖; force, max over contact pairs of "
        "the relative error of the total force; energy, of ½ΣP·v. The ground truth is the "
        "implicit finite-element reference with continuous line contact (on slices where a "
        "scene has only point contacts).\n"
     << md_.str() << "\n---\nData read: " << sources.size() << " files; "
     << "tables in `tables/`, figures in `figures/` (their gnuplot scripts in `figures/src/`), "
        "the numbers in `data/`.\n";
  if (!summary_.missing.empty()) {
    md << "\nFigures not drawn:\n";
    for (const std::string& m : summary_.missing) md << "- " << m << "\n";
  }
  write_file_atomically((folder_ / "report.md").string(), md.str());
  std::ostringstream tex;
  tex << "\\documentclass[a4paper,11pt]{article}\n\\usepackage[T1]{fontenc}\n\\usepackage{lmodern}\n\\usepackage{amsmath}\n"
         "\\usepackage{booktabs}\n\\usepackage{graphicx}\n\\usepackage[margin=2.2cm]{geometry}\n"
         "\\title{fibrecheck: the iterative fibre-contact method, checked}\n\\date{}\n"
         "\\begin{document}\n\\maketitle\n"
      << tex_.str() << "\n\\end{document}\n";
  write_file_atomically((folder_ / "report.tex").string(), tex.str());
  return summary_;
}

}  // namespace fibrecheck
