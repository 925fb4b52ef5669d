// SPDX-License-Identifier: GPL-3.0-or-later
// Tables for papers: a result's CSV table (core/csv.hpp) as a LaTeX table with booktabs rules, the one LaTeX writer
// behind every command's `--format latex` (cli/command.hpp).  The table is the CSV's, cell for cell:
//   - every number keeps the digits the CSV prints (the exact decimals of windows bounds, pattern --window, ...);
//     a number is set in math mode, its exponent e-05 as \times 10^{-5}, nothing rounded;
//   - a value followed by its error bar (lambda1,err1; lambda1,batch_err; a column X then X_err) becomes one column
//     "$v \pm e$" (the bar as core::with_error printed it); a pair X_low,X_high (ci_low,ci_high) becomes "[low, high]";
//   - a column whose number has a status (core::Status: certified, estimated, conjectured; by its name or its
//     decimal twin NAME_decimal) gets a footnote marker in its header, explained under the table with the status's
//     basis and confidence; per-row status columns (status, lower_status, ...) stay columns;
//   - text is escaped (\ & % $ # _ { } ~ ^), an empty cell (undefined, not applicable) prints as --.
// Needs \usepackage{booktabs} in the preamble (said in the output's first comment line).
#pragma once

#include "core/result.hpp"

#include <map>
#include <string>
#include <string_view>

namespace btob::io {

// `s` as LaTeX text: \ & % $ # _ { } ~ ^ escaped, other characters as they are.
std::string latex_text(std::string_view s);

// One CSV cell (a number when it parses as one) as LaTeX: "$-1.5\times 10^{-5}$", "0.25" -> "$0.25$", text escaped.
std::string latex_cell(std::string_view cell);

// The CSV table `csv` (a header line, then rows) as a booktabs `table` with caption `caption`; `status` maps
// column (or dataset) names to the kind of number they hold (Contents::status).  Throws std::invalid_argument on
// a CSV whose rows do not all have the header's number of fields.
std::string latex_table(std::string_view csv, const std::map<std::string, core::Status>& status,
                        std::string_view caption);

// What `--format latex` writes for one table: a comment line with the command that made it and the package it needs,
// then latex_table(csv, status, caption).
std::string latex_document(std::string_view csv, const std::map<std::string, core::Status>& status,
                           std::string_view command_line, std::string_view caption);

}  // namespace btob::io
