// SPDX-License-Identifier: GPL-3.0-or-later
// The one CSV writer of the lab: a table that numpy.genfromtxt(names=True, delimiter=",", dtype=None), pandas and
// Python's csv module all read as it is.  That means
//   - one header line of column names, nothing above it (no "# ..." line: what a run was lives in its manifest),
//   - every row has exactly as many fields as the header (a short row is a programming error: std::logic_error),
//   - no field needs quoting, because genfromtxt does not understand quotes: text fields have ',' replaced by ';',
//     '"' by '\'', line breaks by ' ', and '#' (genfromtxt's comment character) by "no." (see csv_text),
//   - column names are [A-Za-z_][A-Za-z0-9_.]* (numpy drops the '.' from its field names; nothing else changes).
//
//   core::CsvTable t("r,fraction,pattern");
//   t.row({fmt::format("{}", r), fmt::format("{:.6f}", f), pattern});      // every field goes through csv_text
//   t.line(fmt::format("{},{:.6f},{}", r, f, core::csv_text(pattern)));     // or a whole line, fields counted
//   t.line(fmt::format("{},{}", r, core::csv_number(gap)));                  // NaN or inf: an empty cell
//   files.text("NAME.csv", t.text());
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace btob::core {

// A text field made safe for an unquoted CSV: ',' -> ';', '"' -> '\'', '\r' and '\n' -> ' ', '#' -> "no.".
std::string csv_text(std::string_view s);

// A number as a CSV field in the format `spec` (fmt syntax, one argument: "{:.17g}", "{:.6f}"), or "" when it is NaN
// or infinite: no cell is ever "nan" or "inf".  numpy.genfromtxt reads an empty cell of a float column as nan, the
// csv module and pandas as a missing value; a reader that needs to know why a value is undefined finds it in the
// result's manifest (or a column saying so).
std::string csv_number(double v, std::string_view spec = "{:.17g}");

// The fields of one line of such a table: split at every ',' (no field is quoted, so a comma always ends a field).
std::vector<std::string> csv_fields(std::string_view line);

class CsvTable {
 public:
  // `header`: the column names separated by commas; throws std::logic_error on an empty, repeated or ill-formed name.
  explicit CsvTable(std::string_view header);
  explicit CsvTable(const std::vector<std::string>& columns);

  // Appends a row of fields (each passed through csv_text); throws std::logic_error unless there is one per column.
  CsvTable& row(const std::vector<std::string>& fields);
  // Appends a line already joined by commas (text fields passed through csv_text by the caller); throws
  // std::logic_error unless it has one field per column or contains a character that would need quoting.
  CsvTable& line(std::string_view joined);

  const std::vector<std::string>& columns() const { return columns_; }
  std::size_t rows() const { return rows_; }
  // The header line and the rows, each ending in '\n'.
  const std::string& text() const { return text_; }

 private:
  std::vector<std::string> columns_;
  std::string text_;
  std::size_t rows_ = 0;
};

}  // namespace btob::core
