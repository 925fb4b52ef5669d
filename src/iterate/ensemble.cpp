// SPDX-License-Identifier: GPL-3.0-or-later
// Ensembles: r values and initial-condition grids.
#include "iterate/ensemble.hpp"

#include "core/request.hpp"
#include "core/scalar.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <charconv>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace btob::iterate {

std::vector<double> linspace_r(double a, double b, long n) {
  if (n < 1) throw core::InvalidField("r-count", fmt::format("{}", n), "at least 1");
  core::validate_r(a, "r-min");
  core::validate_r(b, "r-max");
  if (b < a) throw core::InvalidField("r-max", fmt::format("{} < r-min = {}", b, a), "r-min <= r-max");
  checked_bytes(static_cast<std::size_t>(n), sizeof(double), "r-count");
  std::vector<double> r(static_cast<std::size_t>(n));
  for (long i = 0; i < n; ++i) r[i] = n == 1 ? a : a + (b - a) * static_cast<double>(i) / static_cast<double>(n - 1);
  if (n > 1) r.back() = b;
  return r;
}

namespace {
template <class T> T linspace_value(const T& a, const T& b, std::size_t i, long n) {
  // linspace_r's expression and order: a + (b - a) * i / (n - 1), the ends exact.
  if (n == 1 || i == 0) return a;
  if (static_cast<long>(i) == n - 1) return b;
  return T(a + T(T(b - a) * T(static_cast<double>(i))) / T(static_cast<double>(n - 1)));
}
}  // namespace

template <class T> T Ensemble::r_at(std::size_t j) const {
  if constexpr (std::is_same_v<T, double>) {
    return r.at(j);
  } else if constexpr (std::is_same_v<T, float>) {
    if (r_text.empty() && r_lo.empty()) return static_cast<float>(r.at(j));
    return static_cast<float>(r_at<core::float128>(j));
  } else {
    if (!r_text.empty()) {
      if (r_text.size() != r.size()) throw std::logic_error("Ensemble: r_text and r differ in size");
      return core::from_decimal<T>(r_text.at(j));
    }
    if (!r_lo.empty()) {
      if (r_index.size() != r.size()) throw std::logic_error("Ensemble: r_index and r differ in size");
      return linspace_value<T>(core::from_decimal<T>(r_lo), core::from_decimal<T>(r_hi), r_index.at(j), r_count);
    }
    return static_cast<T>(r.at(j));
  }
}

template <class T> std::vector<T> Ensemble::r_in() const {
  std::vector<T> out;
  out.reserve(r.size());
  if constexpr (std::is_same_v<T, float>) {
    if (!r_text.empty() || !r_lo.empty()) {  // rounded once from float128, as r_at<float>
      for (const core::float128& v : r_in<core::float128>()) out.push_back(static_cast<float>(v));
      return out;
    }
  } else if constexpr (!std::is_same_v<T, double>) {
    if (r_text.empty() && !r_lo.empty()) {  // a range: its ends parsed once (r_at parses them for every value)
      if (r_index.size() != r.size()) throw std::logic_error("Ensemble: r_index and r differ in size");
      const T lo = core::from_decimal<T>(r_lo), hi = core::from_decimal<T>(r_hi);
      for (std::size_t i : r_index) out.push_back(linspace_value<T>(lo, hi, i, r_count));
      return out;
    }
  }
  for (std::size_t j = 0; j < r.size(); ++j) out.push_back(r_at<T>(j));
  return out;
}

template float Ensemble::r_at<float>(std::size_t) const;
template double Ensemble::r_at<double>(std::size_t) const;
template long double Ensemble::r_at<long double>(std::size_t) const;
template core::float128 Ensemble::r_at<core::float128>(std::size_t) const;
template core::mpfr_float Ensemble::r_at<core::mpfr_float>(std::size_t) const;
template std::vector<float> Ensemble::r_in<float>() const;
template std::vector<double> Ensemble::r_in<double>() const;
template std::vector<long double> Ensemble::r_in<long double>() const;
template std::vector<core::float128> Ensemble::r_in<core::float128>() const;
template std::vector<core::mpfr_float> Ensemble::r_in<core::mpfr_float>() const;

void Ensemble::set_r_range(const core::Decimal& lo, const core::Decimal& hi, long n,
                           const std::vector<std::size_t>* items) {
  std::vector<double> all = linspace_r(lo.value, hi.value, n);
  r_text.clear();
  r_lo = lo.text;
  r_hi = hi.text;
  r_count = n;
  r_index.clear();
  if (!items) {
    r = std::move(all);
    r_index.resize(r.size());
    for (std::size_t i = 0; i < r_index.size(); ++i) r_index[i] = i;
    return;
  }
  r.clear();
  for (std::size_t i : *items) {
    r.push_back(all.at(i));
    r_index.push_back(i);
  }
}

void Ensemble::set_r_list(const std::vector<core::Decimal>& values) {
  r.clear();
  r_text.clear();
  r_lo.clear();
  r_hi.clear();
  r_count = 0;
  r_index.clear();
  for (const core::Decimal& v : values) {
    r.push_back(v.value);
    r_text.push_back(v.text);
  }
}

Ensemble Ensemble::with_r(const std::vector<std::size_t>& indices) const {
  Ensemble e = *this;
  e.r.clear();
  e.r_text.clear();
  e.r_index.clear();
  for (std::size_t i : indices) {
    e.r.push_back(r.at(i));
    if (!r_text.empty()) e.r_text.push_back(r_text.at(i));
    if (!r_lo.empty()) e.r_index.push_back(r_index.at(i));
  }
  return e;
}

std::vector<Vec3<double>> paper_grid() {
  std::vector<Vec3<double>> g;
  for (int gi = 1; gi <= 8; ++gi)
    for (int h = 1; h <= 4; ++h) g.emplace_back(1.0, -(1.0 + 8.0) / (2.0 + gi), -0.1 - h);
  return g;
}

std::vector<Vec3<double>> strip_grid(const core::Grid& g) {
  const std::size_t n = checked_bytes(static_cast<std::size_t>(g.axis1.cells), static_cast<std::size_t>(g.axis2.cells),
                                      sizeof(Vec3<double>), "grid") /
                        sizeof(Vec3<double>);
  std::vector<Vec3<double>> pts;
  pts.reserve(n);
  for (long i = 0; i < g.axis1.cells; ++i)
    for (long j = 0; j < g.axis2.cells; ++j) pts.push_back(g.cell_point(i, j));
  return pts;
}

std::vector<Vec3<double>> strip_grid(long n1, long n2, double w1_min, double w1_max) {
  if (n1 < 1 || n2 < 1) throw core::InvalidField("grid", fmt::format("strip:{}x{}", n1, n2), "at least 1x1 points");
  core::Grid g = core::make_grid(core::GridKind::strip, n1, n2);
  try {
    g.set_range1(w1_min, w1_max, "grid");
  } catch (const core::InvalidField&) {
    throw core::InvalidField("grid", fmt::format("w1 range [{}, {}]", w1_min, w1_max), "finite w1-min < w1-max");
  }
  return strip_grid(g);
}

namespace {
// SplitMix64: a counter-based generator, so point i depends only on (seed, i).
std::uint64_t splitmix(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}
double unit(std::uint64_t bits) { return static_cast<double>(bits >> 11) * 0x1.0p-53; }  // [0, 1)
}  // namespace

std::vector<Vec3<double>> random_points(long n, std::uint64_t seed) {
  if (n < 1) throw core::InvalidField("grid", fmt::format("random:{}", n), "at least 1 point");
  checked_bytes(static_cast<std::size_t>(n), sizeof(Vec3<double>), "grid");
  std::vector<Vec3<double>> g;
  g.reserve(static_cast<std::size_t>(n));
  for (long i = 0; i < n; ++i) {
    const std::uint64_t base = splitmix(seed ^ splitmix(static_cast<std::uint64_t>(i)));
    // Uniform on the sphere (Archimedes: y uniform in [-1, 1], azimuth uniform), folded into Q.
    const double y = 2 * unit(splitmix(base + 1)) - 1;
    const double az = 0.5 * std::numbers::pi * (unit(splitmix(base + 2)) + 0x1.0p-54);  // (0, pi/2)
    const double rho = std::sqrt(std::max(0.0, 1 - y * y));
    g.emplace_back(rho * std::cos(az), y, -rho * std::sin(az));
  }
  return g;
}

namespace {
double parse_double(std::string_view s, const char* field, std::string_view whole) {
  double v = 0;
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || p != s.data() + s.size())
    throw core::InvalidField(field, fmt::format("'{}' in '{}'", s, whole), "a number");
  return v;
}
long parse_long(std::string_view s, const char* field, std::string_view whole) {
  long v = 0;
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || p != s.data() + s.size())
    throw core::InvalidField(field, fmt::format("'{}' in '{}'", s, whole), "a whole number");
  return v;
}
std::vector<std::string_view> split(std::string_view s, char sep) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t k = s.find(sep, start);
    out.push_back(s.substr(start, k == std::string_view::npos ? std::string_view::npos : k - start));
    if (k == std::string_view::npos) break;
    start = k + 1;
  }
  return out;
}
}  // namespace

namespace {
core::InvalidField grid_usage(std::string_view spec, const char* field) {
  return core::InvalidField(field, fmt::format("'{}'", spec),
                            "paper, strip:NxM[:w1min:w1max], random:N or a list x,y,z;x,y,z;...");
}
}  // namespace

core::Grid parse_strip(std::string_view spec, const char* field) {
  static const core::GridSyntax syntax{core::grid_kinds({core::GridKind::strip}), true, 0,
                                       "strip:NxM[:w1min:w1max] with N, M >= 1 and finite w1min < w1max"};
  if (!spec.starts_with("strip:")) throw grid_usage(spec, field);
  return core::parse_grid(spec, syntax, field);
}

std::vector<Vec3<double>> parse_grid(std::string_view spec, std::uint64_t seed, const char* field) {
  const auto usage = [&] { return grid_usage(spec, field); };
  if (spec == "paper") return paper_grid();
  if (spec.starts_with("strip:")) return strip_grid(parse_strip(spec, field));
  if (spec.starts_with("random:")) return random_points(parse_long(spec.substr(7), field, spec), seed);
  if (spec.find(',') != std::string_view::npos) {
    std::vector<Vec3<double>> g;
    for (auto item : split(spec, ';')) {
      if (item.empty()) continue;
      const auto c = split(item, ',');
      if (c.size() != 3) throw usage();
      const double x = parse_double(c[0], field, spec), y = parse_double(c[1], field, spec),
                   z = parse_double(c[2], field, spec);
      core::validate_point(x, y, z, field);
      g.emplace_back(x, y, z);
    }
    if (g.empty()) throw usage();
    return g;
  }
  throw usage();
}

std::size_t checked_bytes(std::size_t count, std::size_t item_bytes, const char* field) {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  const double budget = pages > 0 && page > 0 ? 0.75 * static_cast<double>(pages) * static_cast<double>(page) : 16e9;
  const double need = static_cast<double>(count) * static_cast<double>(item_bytes);
  if (need > budget)
    throw std::length_error(
        fmt::format("{}: needs {:.3g} GB of memory, more than the {:.3g} GB this machine allows "
                    "(3/4 of physical memory); ask for fewer points or iterations",
                    field, need / 1e9, budget / 1e9));
  return static_cast<std::size_t>(need);
}

std::size_t checked_bytes(std::size_t count1, std::size_t count2, std::size_t item_bytes, const char* field) {
  const double n = static_cast<double>(count1) * static_cast<double>(count2);  // exact enough: compared to a budget
  if (n > 1e18) checked_bytes(std::size_t(1) << 62, item_bytes, field);        // throws, naming the field
  return checked_bytes(count1 * count2, item_bytes, field);
}

}  // namespace btob::iterate
