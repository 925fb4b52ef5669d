// SPDX-License-Identifier: GPL-3.0-or-later
// Reading back the CSV tables a module writes (core::CsvTable), for the tests of what the command line writes.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace btob::testing {

// The cells of a CSV text as rows of fields, the header first (CsvTable never quotes: a comma always separates).
inline std::vector<std::vector<std::string>> csv_cells(const std::string& csv) {
  std::vector<std::vector<std::string>> rows;
  for (std::size_t at = 0; at < csv.size();) {
    const std::size_t end = csv.find('\n', at);
    rows.emplace_back(1);
    for (char ch : csv.substr(at, end - at)) {
      if (ch == ',') rows.back().emplace_back();
      else rows.back().back() += ch;
    }
    at = end == std::string::npos ? csv.size() : end + 1;
  }
  return rows;
}

// The column named `name` of a header row (a test failure when there is none).
inline std::size_t csv_column(const std::vector<std::string>& header, const std::string& name) {
  for (std::size_t i = 0; i < header.size(); ++i)
    if (header[i] == name) return i;
  ADD_FAILURE() << "no column " << name;
  return 0;
}

// Every row as long as the header, and no cell a spelled-out non-number ("nan", "inf", "-inf", any case): an
// undefined value is an empty cell.
inline void expect_numbers_or_empty(const std::string& csv, const std::string& what) {
  const auto rows = csv_cells(csv);
  ASSERT_FALSE(rows.empty()) << what;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i].size(), rows[0].size()) << what << " row " << i;
    for (const auto& c : rows[i]) {
      std::string low;
      for (char ch : c) low += static_cast<char>(ch >= 'A' && ch <= 'Z' ? ch - 'A' + 'a' : ch);
      EXPECT_TRUE(low != "nan" && low != "-nan" && low != "inf" && low != "-inf" && low != "+inf")
          << what << " row " << i << ": '" << c << "'";
    }
  }
}

}  // namespace btob::testing
