// SPDX-License-Identifier: GPL-3.0-or-later
// The generic parts of the binding (bind.hpp): keyword conversion, numpy views of a result's arrays, the released
// run with Ctrl-C and progress, and the Python class of results.
#include "bind.hpp"

#include <fmt/format.h>

#include <climits>
#include <pybind11/stl.h>

namespace btob::python {

std::string keyword(const std::string& flag) {
  std::string k = flag;
  for (char& ch : k)
    if (ch == '-') ch = '_';
  return k;
}

namespace {
template <class V> py::dtype dtype_of(const std::vector<V>*) { return py::dtype::of<V>(); }

// The text of one Python number or string: doubles in their shortest exact form (core::field_text).
std::string item_text(py::handle v, bool is_double) {
  if (py::isinstance<py::str>(v)) return v.cast<std::string>();
  if (is_double && !py::isinstance<py::bool_>(v) && PyNumber_Check(v.ptr()))
    return core::field_text(v.cast<double>()).front();
  return py::str(v).cast<std::string>();
}

bool is_sequence(py::handle v) { return !py::isinstance<py::str>(v) && PySequence_Check(v.ptr()); }
}  // namespace

std::vector<std::string> items_of(py::handle value, bool is_double, bool is_vector) {
  if (!is_sequence(value)) return {item_text(value, is_double)};
  std::vector<std::string> out;
  if (is_vector) {
    for (auto e : value) out.push_back(item_text(e, is_double));
    return out;
  }
  // A string field given a sequence: a point (x, y, z) -> "x,y,z"; rows of points -> "x,y,z;x,y,z".
  std::string s;
  for (auto e : value) {
    if (is_sequence(e)) {
      std::string row;
      for (auto x : e) row += (row.empty() ? "" : ",") + item_text(x, true);
      s += (s.empty() ? "" : ";") + row;
    } else {
      s += (s.empty() ? "" : ",") + item_text(e, true);
    }
  }
  return {s};
}

py::array array_view(const core::ArrayView& a, py::handle owner) {
  return std::visit(
      [&](const auto* v) {
        using V = typename std::decay_t<decltype(*v)>::value_type;
        std::vector<py::ssize_t> shape(a.dims.begin(), a.dims.end()), strides(a.dims.size());
        py::ssize_t stride = sizeof(V);
        for (std::size_t i = a.dims.size(); i-- > 0;) {
          strides[i] = stride;
          stride *= static_cast<py::ssize_t>(a.dims[i]);
        }
        py::array arr(dtype_of(v), shape, strides, v->data(), owner);  // a base: numpy views, no copy
        py::detail::array_proxy(arr.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
        return arr;
      },
      a.data);
}

std::string field_doc_lines(const std::vector<core::FieldDoc>& docs, const std::vector<core::FieldTypeDoc>& types) {
  std::string doc;
  for (std::size_t i = 0; i < docs.size(); ++i) {
    const auto& f = docs[i];
    std::string d;
    for (const auto& t : f.defaults) d += (d.empty() ? "" : " ") + t;
    doc += "    " + keyword(f.name) + ": " + types[i].type.python +
           (f.required ? " (required)" : " = " + (d.empty() ? std::string("''") : d)) + ": " + f.help + "\n";
  }
  return doc;
}

py::object attr_value(const core::AttrValue& v) {
  return std::visit([](const auto& x) -> py::object { return py::cast(x); }, v);
}

// Writes the result as the command line does (commands::write, the one writer of results): NAME.h5 (when it has
// arrays), the CSV tables, NAME.json (attributes and the request, so that `btob run NAME.json` reproduces it) and the
// figure (when `plot` and the command draws one), all together: a figure that cannot be drawn is an error and nothing
// is written (the command line warns and keeps the data).
std::vector<std::string> save(const ResultBase& r, const std::string& out, const std::string& name,
                              const std::string& title, bool plot) {
  commands::WriteOptions opts;
  opts.plot = plot;
  opts.plot_required = true;
  std::vector<std::string> written;
  for (const auto& p : commands::write(r, out, name, title, opts)) written.push_back(p.string());
  return written;
}

int threads_value(py::handle v) {
  // A value that is no int (a float, a bool, a string): core's wording, and that it must be an int.
  if (!py::isinstance<py::int_>(v) || py::isinstance<py::bool_>(v))
    throw core::InvalidField("threads", py::repr(v).cast<std::string>(), core::threads_expected() + ", an int");
  int overflow = 0;  // an int beyond long is out of range too; the message quotes it as given
  const long t = PyLong_AsLongAndOverflow(v.ptr(), &overflow);
  if (overflow != 0 || t < 0 || t > core::RunControl::max_threads)
    throw core::InvalidField("threads", py::str(v).cast<std::string>(), core::threads_expected());
  return static_cast<int>(t);
}

int threads_of(const py::kwargs& kw) { return kw.contains("threads") ? threads_value(kw["threads"]) : 0; }

namespace {
// Joins the worker on every exit path, cancelling it first unless it finished (GIL released while joining).
struct WorkerGuard {
  std::thread& t;
  core::CancelToken& token;
  ~WorkerGuard() {
    if (!t.joinable()) return;
    token.cancel();
    py::gil_scoped_release nogil;
    t.join();
  }
};
}  // namespace

void run_released(const std::function<void(const core::RunControl&)>& work, int threads, py::object progress) {
  core::CancelToken token;
  AtomicProgress prog;
  core::RunControl control;
  control.threads = threads;
  control.cancel = &token;
  if (!progress.is_none()) control.progress = &prog;
  std::mutex mu;
  std::condition_variable cv;
  bool finished = false;
  std::exception_ptr error;
  std::thread worker;
  WorkerGuard guard{worker, token};
  {
    py::gil_scoped_release nogil;
    worker = std::thread([&] {
      try {
        work(control);
      } catch (...) {
        error = std::current_exception();
      }
      std::lock_guard<std::mutex> lock(mu);
      finished = true;
      cv.notify_all();
    });
  }
  std::size_t shown = SIZE_MAX;
  const auto forward = [&] {
    const std::size_t d = prog.done.load(), t = prog.total.load();
    if (t > 0 && d != shown) {
      shown = d;
      progress(d, t);  // a Python exception here cancels the run (the guard) and propagates
    }
  };
  for (;;) {
    bool done = false;
    {
      py::gil_scoped_release nogil;
      std::unique_lock<std::mutex> lock(mu);
      done = cv.wait_for(lock, std::chrono::milliseconds(50), [&] { return finished; });
    }
    if (done) break;
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();  // KeyboardInterrupt: the guard cancels, joins
    if (!progress.is_none()) forward();
  }
  {
    py::gil_scoped_release nogil;
    worker.join();
  }
  if (error) std::rethrow_exception(error);
  if (!progress.is_none()) forward();
}

namespace {

// res.NAME: an array (numpy view), a decimal column (decimal.Decimal, None for an empty cell), a string array or
// an attribute, in that order.
py::object result_attribute(py::object self, const std::string& name) {
  const auto& r = self.cast<const ResultBase&>();
  if (const core::ArrayView* a = r.contents.find(name)) return array_view(*a, self);
  for (const auto& d : r.contents.decimals)
    if (d.name == name) {
      const py::object dec = py::module_::import("decimal").attr("Decimal");
      py::list out;
      for (const auto& s : *d.data) out.append(s.empty() ? py::object(py::none()) : dec(s));
      return std::move(out);
    }
  for (const auto& t : r.contents.texts)
    if (t.name == name) return py::cast(*t.data);
  if (auto it = r.attrs.find(name); it != r.attrs.end()) return attr_value(it->second);
  throw py::attribute_error(fmt::format("btob.{} result has no attribute '{}'", r.function, name));
}

// res.status: {name: {"status": certified|estimated|conjectured, "basis": ..., "confidence": ... (estimates)}}
// for every dataset or attribute that says what kind of number it holds (core::Status; NAME.h5's attributes).
py::dict status_dict(const ResultBase& r) {
  py::dict d;
  for (const auto& [name, st] : r.contents.status) {
    py::dict e(py::arg("status") = st.kind, py::arg("basis") = st.basis);
    if (!st.confidence.empty()) e["confidence"] = st.confidence;
    d[py::str(name)] = e;
  }
  return d;
}

py::dict attrs_dict(const ResultBase& r) {
  py::dict d;
  for (const auto& [k, v] : r.attrs) d[py::str(k)] = attr_value(v);
  return d;
}

// The names of a list of Contents entries (arrays, decimals, texts).
template <class List> py::list names_of(const List& list) {
  py::list l;
  for (const auto& a : list) l.append(a.name);
  return l;
}

py::dict array_info(const ResultBase& r, const std::string& name) {
  for (const auto& a : r.contents.arrays)
    if (a.name == name)
      return py::dict(py::arg("dims") = py::tuple(py::cast(a.dims)), py::arg("axes") = a.axes,
                      py::arg("units") = a.units, py::arg("description") = a.description);
  for (const auto* list : {&r.contents.decimals, &r.contents.texts})
    for (const auto& d : *list)
      if (d.name == name)
        return py::dict(py::arg("dims") = py::make_tuple(d.data->size()), py::arg("axes") = d.axes,
                        py::arg("units") = d.units, py::arg("description") = d.description);
  throw py::key_error(name);
}

py::dict request_dict(const ResultBase& r) {
  py::dict d;
  for (const auto& [k, v] : r.request) d[py::str(keyword(k))] = py::cast(v);
  return d;
}

// save() with the GIL released: the plot script is a subprocess.
std::vector<std::string> save_released(const ResultBase& r, const std::string& out, const std::string& name,
                                       const std::string& title, bool plot) {
  py::gil_scoped_release nogil;
  return save(r, out, name, title, plot);
}

// {file name: CSV text}, named by the result's name attribute ("result" without one).
py::dict tables_dict(const ResultBase& r) {
  py::dict d;
  const auto it = r.attrs.find("name");
  const std::string name = it != r.attrs.end() && std::holds_alternative<std::string>(it->second)
                               ? std::get<std::string>(it->second)
                               : std::string("result");
  for (const auto& [role, text] : r.tables) d[py::str(core::table_file(name, role))] = text;
  return d;
}

py::list result_dir(const ResultBase& r) {
  py::list l;
  for (const auto& a : r.contents.arrays) l.append(a.name);
  for (const auto& d : r.contents.decimals) l.append(d.name);
  for (const auto& t : r.contents.texts) l.append(t.name);
  for (const auto& [k, v] : r.attrs) l.append(k);
  for (const char* k : {"attrs", "arrays", "decimals", "texts", "status", "info", "plot", "save", "function", "tables"})
    l.append(k);
  return l;
}

std::string result_repr(const ResultBase& r) {
  std::string s;
  for (const auto& a : r.contents.arrays) {
    std::string dims;
    for (auto d : a.dims) dims += (dims.empty() ? "" : "x") + std::to_string(d);
    s += (s.empty() ? "" : ", ") + a.name + "[" + dims + "]";
  }
  return fmt::format("<btob.{} result: {}>", r.function, s.empty() ? std::string("attributes only") : s);
}

}  // namespace

void bind_result(py::module_& m) {
  py::class_<ResultBase, std::shared_ptr<ResultBase>>(
      m, "Result",
      "A result: its arrays (numpy views of the C++ result, read-only, no copy), exact decimals and attributes are "
      "attributes of this object; res.attrs is the provenance the command line writes to HDF5.")
      .def("__getattr__", &result_attribute)
      .def_property_readonly("attrs", &attrs_dict,
                             "provenance and summary: the attributes the command line writes to NAME.h5 (a dict)")
      .def_property_readonly(
          "arrays", [](const ResultBase& r) { return names_of(r.contents.arrays); },
          "names of the result's arrays (each is also an attribute: res.NAME, a numpy view)")
      .def_property_readonly(
          "decimals", [](const ResultBase& r) { return names_of(r.contents.decimals); },
          "names of the result's exact decimal columns (res.NAME: a list of decimal.Decimal)")
      .def_property_readonly(
          "texts", [](const ResultBase& r) { return names_of(r.contents.texts); },
          "names of the string arrays (word names, overlay names): res.<name> is a list of str")
      .def_property_readonly(
          "status", &status_dict,
          "what kind of number each value computed beyond double (and each estimate) is: "
          "{name: {'status': 'certified'|'estimated'|'conjectured', 'basis': ..., 'confidence': ...}}")
      .def("info", &array_info, "dims, axes, units and description of an array, a decimal column or a string array")
      .def_property_readonly(
          "function", [](const ResultBase& r) { return r.function; },
          "the Python function that made this result (e.g. 'bifurcation')")
      .def_property_readonly(
          "command", [](const ResultBase& r) { return r.command; },
          "the command line's subcommand of the same request (e.g. 'lyapunov-map')")
      .def_property_readonly("request", &request_dict, "the request's fields as text (what the manifest records)")
      .def("_save", &save_released)
      .def_property_readonly("plot_script", [](const ResultBase& r) { return r.plot; })
      .def_property_readonly(
          "plots_from_files", [](const ResultBase& r) { return !r.plot_inputs.empty(); },
          "True when the figure's script reads the command line's files (plot() saves the result "
          "to a temporary folder and shows the PNGs it writes)")
      .def_property_readonly("tables", &tables_dict, "the command line's CSV files of this result: {file name: text}")
      .def("__dir__", &result_dir)
      .def("__repr__", &result_repr);
}

}  // namespace btob::python
