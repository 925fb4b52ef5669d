// SPDX-License-Identifier: GPL-3.0-or-later
// Tables for papers: CSV -> booktabs LaTeX (latex.hpp).
#include "io/latex.hpp"

#include "core/csv.hpp"

#include <fmt/format.h>

#include <regex>
#include <stdexcept>
#include <vector>

namespace btob::io {
namespace {

bool ends_with(const std::string& s, std::string_view tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// An error bar's column: err, error, batch_err, err1, err2, X_err, X_error (core::with_error's second text).
bool is_error_column(const std::string& name) {
  static const std::regex err(R"((err|error|batch_err|err\d+|.+_err|.+_error))");
  return std::regex_match(name, err);
}

// One output column: a CSV column, a value with its bar (a, b), or an interval from column a to column b.
struct Column {
  enum Kind { plain, plus_minus, interval } kind = plain;
  std::size_t a = 0, b = 0;
  std::string header, tail, status_name;  // the header (LaTeX) before and after its status marker; the name its
                                          // status is looked up by
};

// The CSV's columns grouped: X followed by its error bar -> X +- bar; P_low followed by P_high -> [low, high] as P.
std::vector<Column> group_columns(const std::vector<std::string>& h) {
  std::vector<Column> cols;
  for (std::size_t j = 0; j < h.size(); ++j) {
    if (j + 1 < h.size() && is_error_column(h[j + 1]) && !is_error_column(h[j])) {
      cols.push_back({Column::plus_minus, j, j + 1, latex_text(h[j]), " $\\pm$ " + latex_text(h[j + 1]), h[j]});
      ++j;
    } else if (j + 1 < h.size() && ends_with(h[j], "low") && ends_with(h[j + 1], "high") &&
               h[j].substr(0, h[j].size() - 3) == h[j + 1].substr(0, h[j + 1].size() - 4)) {
      std::string prefix = h[j].substr(0, h[j].size() - 3);
      if (!prefix.empty() && prefix.back() == '_') prefix.pop_back();
      cols.push_back({Column::interval, j, j + 1, latex_text(prefix.empty() ? "interval" : prefix), " [low, high]",
                      h[j]});  // status: the ends'

      ++j;
    } else {
      cols.push_back({Column::plain, j, j, latex_text(h[j]), "", h[j]});
    }
  }
  return cols;
}

bool is_number(std::string_view s);

// A number as math-mode LaTeX without the dollars: 1.5e-05 -> 1.5\times 10^{-5}; its digits as the CSV prints them.
std::string math_number(std::string_view cell) {
  const std::size_t e = cell.find_first_of("eE");
  if (e == std::string_view::npos) return std::string(cell);
  const int exponent = std::stoi(std::string(cell.substr(e + 1)));  // e-05 -> -5, e+12 -> 12
  return fmt::format("{}\\times 10^{{{}}}", cell.substr(0, e), exponent);
}

std::string cell_of(const Column& c, const std::vector<std::string>& row) {
  const std::string& a = row[c.a];
  const std::string& b = row[c.b];
  if (c.kind == Column::plain) return latex_cell(a);
  if (a.empty() && b.empty()) return "--";
  if (c.kind == Column::plus_minus && is_number(a) && is_number(b))
    return "$" + math_number(a) + " \\pm " + math_number(b) + "$";
  if (c.kind == Column::plus_minus) return latex_cell(a) + " $\\pm$ " + latex_cell(b);
  return "[" + latex_cell(a) + ", " + latex_cell(b) + "]";
}

bool is_number(std::string_view s) {
  static const std::regex num(R"([+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?)");
  return std::regex_match(s.begin(), s.end(), num);
}

// The status of a column, by its name or its decimal twin's (NAME_decimal), or none.
const core::Status* status_of(const std::map<std::string, core::Status>& status, const std::string& name) {
  for (const std::string& key : {name, name + "_decimal"}) {
    const auto it = status.find(key);
    if (it != status.end() && !name.empty()) return &it->second;
  }
  return nullptr;
}

std::string status_note(const core::Status& s) {
  std::string note = s.kind;
  if (!s.basis.empty()) note += ": " + s.basis;
  if (!s.confidence.empty()) note += " (" + s.confidence + ")";
  return latex_text(note);
}

// The header row with a footnote marker per distinct status, and the notes explaining the markers.
std::pair<std::string, std::string> header_and_notes(const std::vector<Column>& cols,
                                                     const std::map<std::string, core::Status>& status) {
  std::vector<std::string> notes;
  std::string header;
  for (std::size_t j = 0; j < cols.size(); ++j) {
    std::string h = cols[j].header;
    if (const core::Status* s = status_of(status, cols[j].status_name)) {
      const std::string note = status_note(*s);
      std::size_t k = 0;
      while (k < notes.size() && notes[k] != note) ++k;
      if (k == notes.size()) notes.push_back(note);
      h += fmt::format("\\textsuperscript{{{}}}", static_cast<char>('a' + k % 26));
    }
    header += (j ? " & " : "") + h + cols[j].tail;
  }
  std::string text;
  for (std::size_t k = 0; k < notes.size(); ++k)
    text += fmt::format("\\textsuperscript{{{}}}\\,{}.\\par\n", static_cast<char>('a' + k % 26), notes[k]);
  return {header + " \\\\\n", text};
}

std::string column_spec(const std::vector<Column>& cols, const std::vector<std::vector<std::string>>& rows) {
  std::string spec;
  for (const Column& c : cols) {
    bool numeric = c.kind != Column::plain || !rows.empty();
    for (const auto& r : rows)
      if (c.kind == Column::plain && !r[c.a].empty() && !is_number(r[c.a])) numeric = false;
    spec += numeric ? 'r' : 'l';
  }
  return spec;
}

}  // namespace

std::string latex_text(std::string_view s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '\\': out += "\\textbackslash{}"; break;
      case '~': out += "\\textasciitilde{}"; break;
      case '^': out += "\\textasciicircum{}"; break;
      case '&':
      case '%':
      case '$':
      case '#':
      case '_':
      case '{':
      case '}':
        out += '\\';
        out += c;
        break;
      default: out += c;
    }
  }
  return out;
}

std::string latex_cell(std::string_view cell) {
  if (cell.empty()) return "--";
  return is_number(cell) ? "$" + math_number(cell) + "$" : latex_text(cell);
}

std::string latex_table(std::string_view csv, const std::map<std::string, core::Status>& status,
                        std::string_view caption) {
  std::vector<std::vector<std::string>> lines;
  for (std::size_t start = 0; start < csv.size();) {
    std::size_t nl = csv.find('\n', start);
    if (nl == std::string_view::npos) nl = csv.size();
    if (nl > start) lines.push_back(core::csv_fields(csv.substr(start, nl - start)));
    start = nl + 1;
  }
  if (lines.empty()) throw std::invalid_argument("latex_table: an empty CSV table (no header)");
  const std::vector<std::string> head = lines.front();
  lines.erase(lines.begin());
  for (std::size_t i = 0; i < lines.size(); ++i)
    if (lines[i].size() != head.size())
      throw std::invalid_argument(
          fmt::format("latex_table: row {} has {} fields, the header {}", i + 1, lines[i].size(), head.size()));
  const std::vector<Column> cols = group_columns(head);
  const auto [header, notes] = header_and_notes(cols, status);
  std::string t = "\\begin{table}[ht]\n\\centering\n\\begin{tabular}{" + column_spec(cols, lines) + "}\n\\toprule\n" +
                  header + "\\midrule\n";
  for (const auto& row : lines) {
    std::string r;
    for (std::size_t j = 0; j < cols.size(); ++j) r += (j ? " & " : "") + cell_of(cols[j], row);
    t += r + " \\\\\n";
  }
  t += "\\bottomrule\n\\end{tabular}\n";
  if (!notes.empty()) t += "\\par\\smallskip\n{\\footnotesize\n" + notes + "}\n";
  return t + "\\caption{" + latex_text(caption) + "}\n\\end{table}\n";
}

std::string latex_document(std::string_view csv, const std::map<std::string, core::Status>& status,
                           std::string_view command_line, std::string_view caption) {
  std::string comment(command_line);
  for (char& ch : comment)
    if (ch == '\n' || ch == '\r') ch = ' ';
  return "% " + comment + "\n% needs \\usepackage{booktabs}\n" + latex_table(csv, status, caption);
}

}  // namespace btob::io
