// SPDX-License-Identifier: GPL-3.0-or-later
// The lab's CSV writer (csv.hpp): one header line, one field per column on every row, nothing to quote.
#include "core/csv.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <stdexcept>

namespace btob::core {

std::string csv_text(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case ',': out += ';'; break;
      case '"': out += '\''; break;
      case '\r':
      case '\n': out += ' '; break;
      case '#': out += "no."; break;
      default: out += c;
    }
  }
  return out;
}

std::string csv_number(double v, std::string_view spec) {
  return std::isfinite(v) ? fmt::vformat(spec, fmt::make_format_args(v)) : std::string();
}

namespace {
bool valid_name(const std::string& n) {
  if (n.empty() || !(std::isalpha(static_cast<unsigned char>(n[0])) || n[0] == '_')) return false;
  return std::all_of(n.begin(), n.end(),
                     [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.'; });
}

}  // namespace

std::vector<std::string> csv_fields(std::string_view line) {
  std::vector<std::string> f(1);
  for (char c : line) {
    if (c == ',') f.emplace_back();
    else f.back() += c;
  }
  return f;
}

CsvTable::CsvTable(std::string_view header) : CsvTable(csv_fields(header)) {}

CsvTable::CsvTable(const std::vector<std::string>& columns) : columns_(columns) {
  for (std::size_t i = 0; i < columns_.size(); ++i) {
    if (!valid_name(columns_[i]))
      throw std::logic_error(fmt::format("CSV column '{}': expected a name [A-Za-z_][A-Za-z0-9_.]*", columns_[i]));
    if (std::find(columns_.begin(), columns_.begin() + static_cast<long>(i), columns_[i]) !=
        columns_.begin() + static_cast<long>(i))
      throw std::logic_error(fmt::format("CSV column '{}' appears twice", columns_[i]));
  }
  for (std::size_t i = 0; i < columns_.size(); ++i) text_ += (i ? "," : "") + columns_[i];
  text_ += '\n';
}

CsvTable& CsvTable::row(const std::vector<std::string>& fields) {
  if (fields.size() != columns_.size())
    throw std::logic_error(fmt::format("CSV row {}: {} fields for {} columns ({}...)", rows_ + 1, fields.size(),
                                       columns_.size(), columns_.front()));
  for (std::size_t i = 0; i < fields.size(); ++i) text_ += (i ? "," : "") + csv_text(fields[i]);
  text_ += '\n';
  ++rows_;
  return *this;
}

CsvTable& CsvTable::line(std::string_view joined) {
  if (joined.find_first_of("\"#\r\n") != std::string_view::npos)
    throw std::logic_error(
        fmt::format("CSV row {}: '{}' has a character that needs quoting (use csv_text)", rows_ + 1, joined));
  const std::size_t n = static_cast<std::size_t>(std::count(joined.begin(), joined.end(), ',')) + 1;
  if (n != columns_.size())
    throw std::logic_error(
        fmt::format("CSV row {}: {} fields for {} columns: '{}'", rows_ + 1, n, columns_.size(), joined));
  text_ += joined;
  text_ += '\n';
  ++rows_;
  return *this;
}

}  // namespace btob::core
