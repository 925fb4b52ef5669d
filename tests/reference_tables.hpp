// SPDX-License-Identifier: GPL-3.0-or-later
// The paper's tables vendored in analyses/reference/, as the tests read them.  A missing, unreadable, short or
// malformed table throws std::runtime_error naming the file: a test that compares against a reference must fail,
// never pass vacuously, when the reference is not there.
#pragma once

#include <cstddef>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#ifndef BTOB_SOURCE_DIR
#define BTOB_SOURCE_DIR "."
#endif

namespace btob::testing {

struct ReferenceTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;  // every row has header.size() fields (empty fields kept)
};

// Splits a CSV line on commas, keeping empty fields ("1,0.17," has three fields).  The vendored tables
// quote nothing: a field never holds a comma.
inline std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> out(1);
  for (char c : line) {
    if (c == ',') out.emplace_back();
    else if (c != '\r') out.back() += c;
  }
  return out;
}

// Reads analyses/reference/<file>: a header line and exactly `rows` data rows of `columns` fields each.
inline ReferenceTable read_reference_table(const std::string& file, std::size_t rows, std::size_t columns) {
  const std::string path = std::string(BTOB_SOURCE_DIR) + "/analyses/reference/" + file;
  std::ifstream in(path);
  if (!in) throw std::runtime_error("reference table " + path + ": cannot open");
  ReferenceTable t;
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error("reference table " + path + ": empty (no header)");
  t.header = split_csv_line(line);
  if (t.header.size() != columns)
    throw std::runtime_error("reference table " + path + ": header has " + std::to_string(t.header.size()) +
                             " columns, expected " + std::to_string(columns));
  while (std::getline(in, line)) {
    if (line.empty() || line == "\r") continue;
    auto f = split_csv_line(line);
    if (f.size() != columns)
      throw std::runtime_error("reference table " + path + ": row " + std::to_string(t.rows.size() + 1) + " has " +
                               std::to_string(f.size()) + " fields, expected " + std::to_string(columns));
    t.rows.push_back(std::move(f));
  }
  if (t.rows.size() != rows)
    throw std::runtime_error("reference table " + path + ": " + std::to_string(t.rows.size()) + " rows, expected " +
                             std::to_string(rows));
  return t;
}

// Table B.1 (windows_paper_table_B1.csv): n = 1..100, lower bound, upper bound (empty for n = 1), 12 decimals.
inline ReferenceTable table_b1() { return read_reference_table("windows_paper_table_B1.csv", 100, 3); }

}  // namespace btob::testing
