// SPDX-License-Identifier: GPL-3.0-or-later
// Building blocks for one's own analyses: btob.Map(r) (one step of P_r on N points, vectorised) and btob.iterate
// (the batched kernel of src/iterate with its generic recorders: tails of a coordinate, symbols, final states, and
// the whole tail of states and branches from one run).
#include "bind.hpp"
#include "core/map.hpp"
#include "iterate/kernel.hpp"
#include "iterate/recorders.hpp"

#include <fmt/format.h>

namespace btob::python {
namespace {

// A numpy array viewing `v` (moved onto the heap and owned by a capsule: no copy).
template <class V> py::array owned(std::vector<V>&& v, std::vector<py::ssize_t> shape) {
  auto* heap = new std::vector<V>(std::move(v));
  py::capsule owner(heap, [](void* p) { delete static_cast<std::vector<V>*>(p); });
  return py::array(py::dtype::of<V>(), shape, {}, heap->data(), owner);
}

// The rows of an (N, 3) or (3,) array of doubles.
py::array_t<double, py::array::c_style | py::array::forcecast> points_of(py::handle points, const char* field) {
  auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(points);
  if (!a || !((a.ndim() == 2 && a.shape(1) == 3) || (a.ndim() == 1 && a.shape(0) == 3)))
    throw core::InvalidField(field, py::str(py::repr(points)).cast<std::string>().substr(0, 80),
                             "an array of shape (N, 3) or (3,) of directions x,y,z");
  return a;
}

struct Map {
  double r;
  explicit Map(double r_) : r(r_) { core::require_r(r, "r"); }

  // One step u -> M_s u = P_s u / r (not normalised, in the quadrant Q) of every row, and the branch s of each:
  // the batched kernel's step bit for bit (iterate::kernel_step).
  py::tuple step(py::handle points) const {
    const auto a = points_of(points, "points");
    const std::size_t n = a.ndim() == 2 ? static_cast<std::size_t>(a.shape(0)) : 1;
    const double* p = a.data();
    for (std::size_t i = 0; i < n; ++i) core::validate_point(p[3 * i], p[3 * i + 1], p[3 * i + 2], "points");
    std::vector<double> out(3 * n);
    std::vector<std::uint8_t> sym(n);
    {
      py::gil_scoped_release nogil;
      for (std::size_t i = 0; i < n; ++i) {
        const auto s = iterate::kernel_step(core::Vec3<double>(p[3 * i], p[3 * i + 1], p[3 * i + 2]), r);
        for (int k = 0; k < 3; ++k) out[3 * i + k] = s.u(k);
        sym[i] = static_cast<std::uint8_t>(s.symbol);
      }
    }
    const auto ni = static_cast<py::ssize_t>(n);
    if (a.ndim() == 1) return py::make_tuple(owned(std::move(out), {3}), static_cast<int>(sym[0]));
    return py::make_tuple(owned(std::move(out), {ni, 3}), owned(std::move(sym), {ni}));
  }
  py::array matrix(int i) const {
    const core::Mat3<double> P = core::P<double>(i, r);
    std::vector<double> v(9);
    for (int row = 0; row < 3; ++row)
      for (int col = 0; col < 3; ++col) v[3 * row + col] = P(row, col);
    return owned(std::move(v), {3, 3});
  }
};

template <class T, class Rec>
void run_kernel(const iterate::Ensemble& e, long iterations, Rec& rec, const core::RunControl& c) {
  iterate::RunOptions opt;
  opt.threads = c.threads;
  opt.progress = c.progress;
  opt.cancel = c.cancel;
  iterate::run<T>(e, iterations, rec, opt);
}

template <class Rec>
void run_precision(const std::string& precision, const iterate::Ensemble& e, long it, Rec& rec,
                   const core::RunControl& c) {
  if (precision == "float") run_kernel<float>(e, it, rec, c);
  else if (precision == "double") run_kernel<double>(e, it, rec, c);
  else if (precision == "long-double") run_kernel<long double>(e, it, rec, c);
  else throw core::InvalidField("precision", "'" + precision + "'", "float, double or long-double");
}

// The orbits of btob.iterate, every r against every point, each checked as the command line checks it; also
// refuses the run's sizes and precision before any work.
iterate::Ensemble orbits_of(py::handle r, py::handle points, long iterations, long tail, const std::string& precision) {
  iterate::Ensemble e;
  for (const auto& t : items_of(r, true, true)) {
    e.r.push_back(core::parse_double(t, "r"));
    core::require_r(e.r.back(), "r");
  }
  const auto a = points_of(points, "points");
  const std::size_t n = a.ndim() == 2 ? static_cast<std::size_t>(a.shape(0)) : 1;
  for (std::size_t i = 0; i < n; ++i) {
    const double* p = a.data() + 3 * i;
    e.initial.push_back(core::parse_point(fmt::format("{},{},{}", core::field_text(p[0]).front(),
                                                      core::field_text(p[1]).front(), core::field_text(p[2]).front()),
                                          "points"));
  }
  if (e.r.empty() || e.initial.empty()) throw core::InvalidField("points", "no orbits", "at least one r and one point");
  if (iterations < 1) throw core::InvalidField("iterations", std::to_string(iterations), "at least 1");
  if (tail < 1 || tail > iterations)
    throw core::InvalidField("tail", std::to_string(tail), fmt::format("1..iterations = {}", iterations));
  if (precision != "float" && precision != "double" && precision != "long-double")
    throw core::InvalidField("precision", "'" + precision + "'", "float, double or long-double");
  return e;
}

py::object iterate_orbits(py::handle r, py::handle points, long iterations, const std::string& record,
                          const std::string& coord, long tail, const std::string& precision, int threads,
                          py::object progress) {
  const iterate::Ensemble e = orbits_of(r, points, iterations, tail, precision);
  const bool scalar_r = !PySequence_Check(r.ptr()) && !py::isinstance<py::array>(r);
  std::vector<py::ssize_t> shape;
  if (!scalar_r) shape.push_back(static_cast<py::ssize_t>(e.r.size()));
  shape.push_back(static_cast<py::ssize_t>(e.initial.size()));
  // One kernel run in the requested precision, feeding `rec`, with the GIL released and Ctrl-C watched.
  const auto run = [&](auto& rec) {
    run_released([&](const core::RunControl& c) { run_precision(precision, e, iterations, rec, c); }, threads,
                 progress);
  };
  if (record == "tail") {
    iterate::TailRecorder rec(iterate::parse_coord(coord, "coord"), e.orbits(), iterations, tail);
    run(rec);
    shape.push_back(tail);
    return owned(std::move(rec.out), shape);
  }
  if (record == "symbols") {
    iterate::SymbolRecorder rec(e.orbits(), iterations - tail + 1, iterations);
    run(rec);
    shape.push_back(tail);
    return owned(std::move(rec.out), shape);
  }
  if (record == "final") {
    iterate::FinalRecorder rec(e.orbits(), iterations);
    run(rec);
    std::vector<double> flat(3 * rec.out.size());
    for (std::size_t o = 0; o < rec.out.size(); ++o)
      for (int k = 0; k < 3; ++k) flat[3 * o + k] = rec.out[o](k);
    shape.push_back(3);
    return owned(std::move(flat), shape);
  }
  if (record == "orbit") {
    // The whole tail of every orbit from one kernel run: one recorder per quantity, all fed by the same steps
    // (iterate::Both), so each array is bit for bit that of its own record (tail of theta / phi, symbols, final).
    iterate::StateTailRecorder states(e.orbits(), iterations, tail);
    iterate::TailRecorder theta(iterate::Coord::theta, e.orbits(), iterations, tail);
    iterate::TailRecorder phi(iterate::Coord::phi, e.orbits(), iterations, tail);
    iterate::SymbolRecorder branch(e.orbits(), iterations - tail + 1, iterations);
    iterate::OrbitRecorders rec(states, theta, phi, branch);
    run(rec);
    shape.push_back(tail);
    py::dict out;
    out["x"] = owned(std::move(states.x), shape);
    out["y"] = owned(std::move(states.y), shape);
    out["z"] = owned(std::move(states.z), shape);
    out["branch"] = owned(std::move(branch.out), shape);
    out["theta"] = owned(std::move(theta.out), shape);
    out["phi"] = owned(std::move(phi.out), shape);
    return std::move(out);
  }
  throw core::InvalidField("record", "'" + record + "'", "tail, symbols, final or orbit");
}

}  // namespace

void bind_blocks(py::module_& m) {
  py::class_<Map>(m, "Map", "The b-to-b map P_r (Theorem 3.3): Map(r).step(points) applies one step to N points")
      .def(py::init<double>(), py::arg("r"))
      .def_readonly("r", &Map::r, "the restitution coefficient r, in (0, 1)")
      .def("step", &Map::step, py::arg("points"),
           "One step of every row x,y,z (an (N, 3) array, or one point (3,)): returns (P_s u / r, s), the image not "
           "normalised and in the quadrant Q = {x >= 0, z <= 0}, bit for bit the batched kernel's step (which "
           "divides P_s by r: same direction), and the branch s in {1, 2, 3} (uint8) of each row")
      .def("matrix", &Map::matrix, py::arg("i"), "The matrix P_i (i = 1, 2, 3) at this r")
      .def("__repr__", [](const Map& mp) { return fmt::format("btob.Map(r={})", core::field_text(mp.r).front()); });
  m.def("_iterate", &iterate_orbits, py::arg("r"), py::arg("points"), py::arg("iterations"), py::arg("record"),
        py::arg("coord"), py::arg("tail"), py::arg("precision"), py::arg("threads"), py::arg("progress"));
}

}  // namespace btob::python
