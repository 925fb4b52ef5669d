// SPDX-License-Identifier: GPL-3.0-or-later
// The grid type's parser, axes and points (core/grid.hpp).
#include "core/grid.hpp"

#include "core/fields.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <numbers>
#include <optional>

#include "core/coords.hpp"
#include "core/request.hpp"

namespace btob::core {

const char* grid_kind_name(GridKind kind) {
  switch (kind) {
    case GridKind::strip: return "strip";
    case GridKind::sphere: return "sphere";
    case GridKind::angles: return "angles";
    default: return "boxes";
  }
}

std::vector<double> GridAxis::centres() const {
  std::vector<double> v(static_cast<std::size_t>(cells));
  for (long i = 0; i < cells; ++i) v[static_cast<std::size_t>(i)] = centre(i);
  return v;
}

std::vector<double> GridAxis::edges() const {
  std::vector<double> v(static_cast<std::size_t>(cells) + 1);
  for (long i = 0; i <= cells; ++i) v[static_cast<std::size_t>(i)] = edge(i);
  return v;
}

Vec3<double> Grid::point(double a, double b) const {
  switch (kind) {
    case GridKind::strip: return from_strip<double>(a, b);
    case GridKind::sphere: return from_height<double>(a, b);
    default: return from_angles<double>(a, b);
  }
}

namespace {
constexpr double kHalfPi = std::numbers::pi / 2;

// The axes of each kind: range, name, units, meaning (cell centres).
void set_axes(Grid& g, long n1, long n2) {
  const auto axis = [](long n, double lo, double hi, const char* name, const char* units, const char* meaning) {
    return GridAxis{n, lo, hi, name, units, meaning};
  };
  switch (g.kind) {
    case GridKind::strip:
      g.axis1 = axis(n1, -2, 2, "w1", "1", "strip coordinate w1 (eq. (6.4)), cell centres");
      g.axis2 = axis(n2, -1, 1, "w2", "1", "strip coordinate w2 in [-1, 1] (eq. (6.4)), cell centres");
      break;
    case GridKind::sphere:
      g.axis1 = axis(n1, 0, kHalfPi, "theta", "rad", "polar angle theta in [0, pi/2], cell centres");
      g.axis2 =
          axis(n2, -1, 1, "y", "1", "height y = -cos(phi) in [-1, 1] (equal-area chart of the sphere), cell centres");
      break;
    case GridKind::angles:
      g.axis1 = axis(n1, 0, kHalfPi, "theta", "rad", "polar angle theta in [0, pi/2], cell centres");
      g.axis2 = axis(n2, 0, std::numbers::pi, "phi", "rad", "angle phi in [0, pi], cell centres");
      break;
    default:
      g.axis1 = axis(n1, 0, 1, "box 1", "1", "first chart coordinate, in boxes");
      g.axis2 = axis(n2, 0, 1, "box 2", "1", "second chart coordinate, in boxes");
  }
}

std::optional<GridKind> kind_of(std::string_view name) {
  for (GridKind k : {GridKind::strip, GridKind::sphere, GridKind::angles})
    if (name == grid_kind_name(k)) return k;
  return std::nullopt;
}

// a < b with a, b and the width b - a finite (the centres' formula multiplies by b - a).
bool finite_range(double a, double b) { return std::isfinite(a) && std::isfinite(b) && a < b && std::isfinite(b - a); }

template <class T> std::optional<T> number(std::string_view s) {
  T v{};
  const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || p != s.data() + s.size() || s.empty()) return std::nullopt;
  return v;
}
}  // namespace

Grid make_grid(GridKind kind, long n1, long n2) {
  Grid g;
  g.kind = kind;
  set_axes(g, n1, n2);
  return g;
}

void Grid::set_range1(double lo, double hi, const char* field) {
  if (!finite_range(lo, hi)) throw InvalidField(field, fmt::format("[{}, {}]", lo, hi), "finite a < b");
  require_distinct(lo, hi, axis1.cells, field, "its range");  // distinct cell centres
  axis1.lo = lo, axis1.hi = hi;
}

Grid parse_grid(std::string_view spec, const GridSyntax& syntax, const char* field) {
  const auto bad = [&] { return InvalidField(field, fmt::format("'{}'", spec), syntax.expected); };
  Grid g;
  std::string_view rest = spec;
  if (const auto colon = spec.find(':'); colon != std::string_view::npos) {
    const auto k = kind_of(spec.substr(0, colon));
    if (!k) throw bad();
    g.kind = *k;
    rest = spec.substr(colon + 1);
  } else {
    g.kind = GridKind::boxes;
  }
  if (!syntax.accepts(g.kind)) throw bad();
  // rest = NxM[:a:b]
  std::string_view dims = rest, range;
  if (const auto colon = rest.find(':'); colon != std::string_view::npos)
    dims = rest.substr(0, colon), range = rest.substr(colon + 1);
  const auto x = dims.find('x');
  if (x == std::string_view::npos) throw bad();
  const auto n1 = number<long>(dims.substr(0, x)), n2 = number<long>(dims.substr(x + 1));
  if (!n1 || !n2) throw bad();
  if (*n1 < 1 || *n2 < 1 || (syntax.max_side > 0 && (*n1 > syntax.max_side || *n2 > syntax.max_side))) throw bad();
  g = make_grid(g.kind, *n1, *n2);
  if (rest.size() != dims.size()) {
    const auto colon = range.find(':');
    if (!syntax.ranges || g.kind != GridKind::strip || colon == std::string_view::npos) throw bad();
    const auto a = number<double>(range.substr(0, colon)), b = number<double>(range.substr(colon + 1));
    if (!a || !b || !finite_range(*a, *b)) throw bad();
    require_distinct(*a, *b, *n1, field, "w1min:w1max");  // distinct cell centres
    g.axis1.lo = *a, g.axis1.hi = *b, g.has_range = true;
  }
  return g;
}

std::string grid_spec(const Grid& g) {
  if (g.kind == GridKind::boxes) return fmt::format("{}x{}", g.axis1.cells, g.axis2.cells);
  if (g.kind == GridKind::strip)
    return fmt::format("strip:{}x{}:{}:{}", g.axis1.cells, g.axis2.cells, g.axis1.lo, g.axis1.hi);
  return fmt::format("{}:{}x{}", grid_kind_name(g.kind), g.axis1.cells, g.axis2.cells);
}

}  // namespace btob::core
