// SPDX-License-Identifier: GPL-3.0-or-later
// The Python binding of the request/result contract (core/request.hpp, core/result.hpp): ONE template binds any
// request type.  Keyword arguments are the request's fields() named as their flags with '-' -> '_', parsed by the
// field parsers of core/fields.hpp (the same defaults, the same one-line errors, raised as ValueError); the run
// happens on a worker thread with the GIL released while the caller polls for Ctrl-C and forwards progress; the
// result is a Python object whose attributes are the Contents' arrays as numpy views of the C++ vectors (no copy),
// its decimals (multiprecision values as decimal.Decimal) and its attributes.
#pragma once

#include "commands/commands.hpp"
#include "commands/execute.hpp"
#include "core/cancel.hpp"
#include "core/estimate.hpp"
#include "core/field_types.hpp"
#include "core/fields.hpp"
#include "core/request.hpp"
#include "core/result.hpp"
#include "core/run.hpp"
#include "extras/extras.hpp"
#include "io/checkpoint.hpp"
#include "io/io.hpp"
#include "io/rates.hpp"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

namespace btob::python {

namespace py = pybind11;

// A flag name as a Python keyword: "r-min" -> "r_min".
std::string keyword(const std::string& flag);

using Args = core::Args;  // fields as a manifest records them (core/fields.hpp)
// What Python holds of one result: the record the command line writes (commands/execute.hpp), the result itself
// kept beside it in commands::Recorded (its Contents are views into it).
using ResultBase = commands::Record;

// The numpy view of one array of `owner`'s contents; its base is `owner` (no copy, read-only).
py::array array_view(const core::ArrayView& a, py::handle owner);
// The Python value of an attribute (str, float, int).
py::object attr_value(const core::AttrValue& v);

// Text items of a Python value for a field of type T (then parsed by core::set_field).
std::vector<std::string> items_of(py::handle value, bool is_double, bool is_vector);

// Python values -> request fields, by keyword; records which keywords were used.
struct KwargsApplier {
  const py::kwargs* kw;
  std::set<std::string>* used;
  std::set<std::string>* missing;
  template <class T> void operator()(const std::string& name, T& member, const std::string& help) {
    set(name, member, help, false);
  }
  template <class T> void operator()(const std::string& name, T& member, const std::string& help, core::Required) {
    set(name, member, help, true);
  }
  template <class T> void operator()(const std::string& name, T& member, const std::string& help, core::Positional) {
    set(name, member, help, true);  // a positional argument on the command line, a required keyword here
  }
  template <class T> void set(const std::string& name, T& member, const std::string&, bool required) {
    static_assert(core::is_field_type_v<T>, "request fields must be of a type core/fields.hpp parses");
    const std::string k = keyword(name);
    if (!kw->contains(k.c_str())) {
      if (required) missing->insert(k);
      return;
    }
    used->insert(k);
    const py::handle v = (*kw)[k.c_str()];
    if constexpr (std::is_same_v<T, bool>) {
      if (!py::isinstance<py::bool_>(v))
        throw core::InvalidField(name, py::str(py::repr(v)).cast<std::string>(), "True or False");
      member = v.cast<bool>();
    } else {
      constexpr bool is_double = std::is_same_v<T, double> || std::is_same_v<T, std::vector<double>> ||
                                 std::is_same_v<T, core::Decimal> || std::is_same_v<T, std::vector<core::Decimal>>;
      constexpr bool is_vector = std::is_same_v<T, std::vector<double>> ||
                                 std::is_same_v<T, std::vector<std::string>> ||
                                 std::is_same_v<T, std::vector<core::Decimal>>;
      core::set_field(member, items_of(v, is_double, is_vector), name);
    }
  }
};

// "name: type = default: help" lines for the docstring (type the Python annotation; "(required)" for a field that
// must be given, no default), from core's documentation of the fields and their types (same order).
std::string field_doc_lines(const std::vector<core::FieldDoc>& docs, const std::vector<core::FieldTypeDoc>& types);

// "btob.f(k='v', flag=True, values=['1', '2'], ...)": the provenance attribute `command` of a Python result, a
// call that pasted into Python reproduces the request (text values in quotes, lists for list fields, booleans
// as True/False: every form the keyword parser reads back to the same field).
struct CallWriter {
  std::string* text;
  template <class T, class... Tag> void operator()(const std::string& name, T& member, const std::string&, Tag...) {
    std::string v;
    if constexpr (std::is_same_v<T, bool>) {
      v = member ? "True" : "False";
    } else if constexpr (std::is_same_v<T, std::vector<double>> || std::is_same_v<T, std::vector<std::string>> ||
                         std::is_same_v<T, std::vector<core::Decimal>>) {
      for (const auto& t : core::field_text(member)) v += (v.empty() ? "" : ", ") + quoted(t);
      v = "[" + v + "]";
    } else {
      for (const auto& t : core::field_text(member)) v += (v.empty() ? "" : " ") + t;
      v = quoted(v);
    }
    *text += (text->empty() ? "" : ", ") + keyword(name) + "=" + v;
  }
  static std::string quoted(const std::string& t) { return py::repr(py::str(t)).cast<std::string>(); }
};

// Progress of a run, written by its threads and read by the waiting Python thread.
struct AtomicProgress : core::ProgressSink {
  std::atomic<std::size_t> done{0}, total{0};
  void update(std::size_t d, std::size_t t) override {
    total.store(t, std::memory_order_relaxed);
    done.store(d, std::memory_order_relaxed);
  }
};

// Runs `work(control)` on a worker thread with the GIL released.  The caller wakes every `slice` (<= 100 ms),
// takes the GIL to call PyErr_CheckSignals() and the progress callback (None or callable(done, total)); on a
// Python exception (KeyboardInterrupt) it cancels the run, joins the worker and re-raises.
void run_released(const std::function<void(const core::RunControl&)>& work, int threads, py::object progress);

// Checks threads (0 = all cores, else 1..RunControl::max_threads, an int); ValueError with core's wording otherwise.
int threads_value(py::handle v);
int threads_of(const py::kwargs& kw);

namespace detail {

// The request of a call: commands::Spec<Req>::defaults() with the keywords applied; an unknown keyword or a missing
// required one is a TypeError naming it (threads and progress are the call's, not the request's).
template <class Req> Req request_of(const py::kwargs& kw) {
  using R = commands::Spec<Req>;
  Req req = R::defaults();
  std::set<std::string> used{"threads", "progress"}, missing;
  if constexpr (core::Sweep<Req>) used.insert("resume");
  req.fields(KwargsApplier{&kw, &used, &missing});
  for (auto item : kw) {
    const std::string k = item.first.cast<std::string>();
    if (!used.count(k))
      throw py::type_error(std::string(R::function) + "() got an unexpected keyword argument '" + k + "'");
  }
  if (!missing.empty())
    throw py::type_error(std::string(R::function) + "() missing required keyword argument '" + *missing.begin() + "'");
  return req;
}

// The call that reproduces a request, "btob.f(k='v', ...)": the provenance attribute `command` of a Python result.
template <class Req> std::string call_text(Req req) {
  std::string call;
  req.fields(CallWriter{&call});
  return "btob." + std::string(commands::Spec<Req>::function) + "(" + call + ")";
}

// resume= of a sweep: the checkpoint's path (str or os.PathLike), "" when absent or None.
inline std::string resume_of(const py::kwargs& kw) {
  if (!kw.contains("resume") || kw["resume"].is_none()) return "";
  return py::str(py::module_::import("os").attr("fspath")(kw["resume"]));
}

// The checkpoint of resume= for the request as it runs (io/checkpoint.hpp: the command line's file, identity and
// refusal, keyed by the command's name and the request's fields): ValueError with its one line when the file belongs
// to another request or build, or another run uses it.
template <class Req> std::unique_ptr<io::Checkpoint> open_resume(const Req& req, const std::string& path) {
  auto cp = std::make_unique<io::Checkpoint>();
  cp->path = path;
  Args args;
  Req copy = req;
  copy.fields(core::ArgsWriter{&args});
  cp->identity = io::checkpoint_identity(commands::Spec<Req>::command, args);
  if (const std::string why = io::open_checkpoint_file(*cp); !why.empty()) throw py::value_error(why);
  return cp;
}

// One call of btob.<function>(**kw), through the one path of commands/execute.hpp: request -> ready (prepare,
// validate) -> compute (released) -> record -> Result.  A sweep given resume="DIR/NAME.checkpoint" keeps its
// finished items there and continues from them; the file is removed once the result is complete and kept when the
// run stops (KeyboardInterrupt, an error, a kill).
template <class Req> py::object call(py::kwargs kw) {
  using S = commands::Spec<Req>;
  Req req = request_of<Req>(kw);
  const int threads = threads_of(kw);
  commands::ready(req);
  std::unique_ptr<io::Checkpoint> cp;
  if constexpr (core::Sweep<Req>)
    if (const std::string path = resume_of(kw); !path.empty()) cp = open_resume(req, path);
  // The overlays (window bounds in MPFR, ~0.5 s) are computed on the worker after the run, as the command
  // line does, not on this thread: while it holds the GIL and computes, Ctrl-C is not seen.
  std::shared_ptr<commands::Recorded<Req>> rec;
  run_released(
      [&](const core::RunControl& c) {
        commands::How how;
        how.control = c;
        how.checkpoint = cp.get();
        rec = commands::compute(req, how);
      },
      threads, kw.contains("progress") ? py::object(kw["progress"]) : py::object(py::none()));
  if (cp) io::remove_checkpoint(*cp);
  commands::record(*rec, commands::Provenance{call_text(req), S::stem_of(req), "", core::thread_count(threads)});
  return py::cast(std::static_pointer_cast<ResultBase>(rec));
}

// The bound functions, their commands and keyword arguments with their defaults as text, for tests that must
// cover every request ({function: command}, {function: [(keyword, default)]}).
template <class Req> void list_function(py::module_& m, Req defaults) {
  using R = commands::Spec<Req>;
  if (!py::hasattr(m, "_commands")) m.attr("_commands") = py::dict();
  if (!py::hasattr(m, "_fields")) m.attr("_fields") = py::dict();
  m.attr("_commands")[R::function] = R::command;
  Args fields;
  defaults.fields(core::ArgsWriter{&fields});
  py::list kws;
  for (const auto& [name, values] : fields) {
    py::list texts;
    for (const auto& t : values) texts.append(py::str(t));
    kws.append(py::make_tuple(py::str(keyword(name)), texts));
  }
  m.attr("_fields")[R::function] = kws;
  // (keyword, Python annotation, default texts, required) per field, and whether it takes resume=: btob/__init__.py
  // builds each function's inspect.Signature from it (help(), IDE completion, a notebook's shift-tab).
  if (!py::hasattr(m, "_signatures")) m.attr("_signatures") = py::dict();
  std::vector<core::FieldDoc> docs;
  std::vector<core::FieldTypeDoc> types;
  defaults.fields(core::DocLister{&docs});
  defaults.fields(core::TypeLister{&types});
  py::list params;
  for (std::size_t i = 0; i < docs.size(); ++i) {
    py::list texts;
    for (const auto& t : docs[i].defaults) texts.append(py::str(t));
    params.append(
        py::make_tuple(py::str(keyword(docs[i].name)), py::str(types[i].type.python), texts, docs[i].required));
  }
  m.attr("_signatures")[R::function] = py::make_tuple(params, core::Sweep<Req>);
}

// A sweep's cost from a sample of its own items (32 items and 0.2 s, or 1 s; core/estimate.hpp), for
// btob.estimate(function, **kwargs):
// _btob._estimators[function](**kwargs) -> dict(items, sampled, sample_seconds, predicted_seconds, bytes,
// peak_bytes); the same keywords as the function (threads included), nothing returned but the numbers.  The sweeps'
// names are also in _btob._sweeps (the functions that take resume=).
template <class Req> void bind_estimate(py::module_& m) {
  using R = commands::Spec<Req>;
  if (!py::hasattr(m, "_estimators")) m.attr("_estimators") = py::dict();
  if (!py::hasattr(m, "_sweeps")) m.attr("_sweeps") = py::set();
  m.attr("_sweeps").attr("add")(R::function);
  m.attr("_estimators")[R::function] = py::cpp_function([](py::kwargs kw) -> py::dict {
    Req req = request_of<Req>(kw);
    const int threads = threads_of(kw);
    commands::ready(req);
    core::SweepEstimate e;
    const auto start = static_cast<std::size_t>(core::thread_count(threads));
    run_released([&](const core::RunControl& c) { e = core::estimate_sweep(req, c, 1, start); }, threads, py::none());
    py::dict d;
    d["items"] = e.items;
    d["sampled"] = e.sampled;
    d["sample_seconds"] = e.sample_seconds;
    d["predicted_seconds"] = e.predicted_seconds;
    d["bytes"] = e.bytes;
    d["peak_bytes"] = 2 * e.bytes;
    d["model"] = e.model;  // a sized sweep's fit ("extrapolated from sizes ..."), else ""
    return d;
  });
}

// The cost of a request that is not a sweep (core/work.hpp): its work at the cached, else calibrated, route rates
// (io/rates.hpp).  _btob._estimators[function](**kwargs) -> dict(terms, predicted_seconds, threads, upper_bound,
// bytes, peak_bytes), terms a list of dict(route, units, what, units_per_second, cached).
template <class Req> void bind_work_estimate(py::module_& m) {
  using R = commands::Spec<Req>;
  if (!py::hasattr(m, "_estimators")) m.attr("_estimators") = py::dict();
  m.attr("_estimators")[R::function] = py::cpp_function([](py::kwargs kw) -> py::dict {
    Req req = request_of<Req>(kw);
    const int threads = threads_of(kw);
    commands::ready(req);
    io::WorkEstimate e;
    const int used = core::thread_count(threads);
    run_released([&](const core::RunControl& c) { e = io::estimate_work(work(req), c, used); }, threads, py::none());
    py::list terms;
    for (std::size_t i = 0; i < e.work.terms.size(); ++i) {
      py::dict t;
      t["route"] = e.work.terms[i].route;
      t["units"] = e.work.terms[i].units;
      t["what"] = e.work.terms[i].what;
      t["units_per_second"] = e.rates[i].units_per_second;
      t["cached"] = e.rates[i].cached;
      t["model"] = e.rates[i].model;  // a sized term's fit ("extrapolated from sizes ..."), else ""
      terms.append(t);
    }
    py::dict d;
    d["terms"] = terms;
    d["predicted_seconds"] = e.predicted_seconds;
    d["threads"] = e.threads;
    d["upper_bound"] = e.work.bound;
    d["bytes"] = e.work.output_bytes;
    d["peak_bytes"] = e.work.peak_bytes;
    return d;
  });
}

}  // namespace detail

// Binds the declared request Req (commands/commands.hpp) as btob.<function>: kwargs -> Req -> the one path of
// commands/execute.hpp -> Result; lists it in _btob._functions (in the declarations' order).
template <class Req> void bind(py::module_& m) {
  using R = commands::Spec<Req>;
  std::string doc = std::string(R::summary) + "\n\nKeyword arguments (the command line's flags, '-' -> '_'):\n";
  Req defaults = R::defaults();
  std::vector<core::FieldDoc> docs;
  std::vector<core::FieldTypeDoc> types;
  defaults.fields(core::DocLister{&docs});
  defaults.fields(core::TypeLister{&types});
  doc += field_doc_lines(docs, types);
  doc +=
      "    threads: int = 0: OpenMP threads (0: all cores)\n"
      "    progress: bool | Callable = False: True (tqdm), or callable(done, total)\n";
  if constexpr (core::Sweep<Req>)
    doc +=
        "    resume: str | None = None: 'DIR/NAME.checkpoint': keep the finished items in that file and continue from "
        "it (the "
        "command line's --resume; refused for another request or build; removed once the result is complete)\n";
  m.def(R::function, &detail::call<Req>, doc.c_str());
  if (!py::hasattr(m, "_functions")) m.attr("_functions") = py::list();
  m.attr("_functions").attr("append")(R::function);
  detail::list_function(m, defaults);
  if constexpr (core::Sweep<Req>) detail::bind_estimate<Req>(m);
  else if constexpr (core::Costed<Req>) detail::bind_work_estimate<Req>(m);
}

}  // namespace btob::python
