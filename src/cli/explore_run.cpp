// SPDX-License-Identifier: GPL-3.0-or-later
// The explorer's API from the registry (explore.hpp, GET /api/run): a served command's request filled from the query
// by its fields' flag names, run through commands/execute.hpp's one path, and its Record answered as JSON.  No
// command is named here: the served ones are those whose Spec says so (commands/commands.hpp).
#include "cli/command.hpp"
#include "cli/explore.hpp"
#include "commands/commands.hpp"
#include "commands/execute.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

namespace btob::cli::explore {
namespace {
using nlohmann::json;

// The query's parameters other than the explorer's own (command, session), as the fields' text: a scene's Args.
Args field_args(const Params& p) {
  Args args;
  for (const auto& [k, v] : p)
    if (k != "command" && k != "session") args.emplace_back(k, std::vector<std::string>{v});
  return args;
}

// The record as JSON: {"command", "request": {field: [text...]}, "attrs": {...}, "arrays": {name: {"dims", "axes",
// "units", "data"}}, "texts": {name: [...]}, "decimals": {name: [...]}}.  Arrays flat, row-major as `dims` says; a
// number that is not finite is null (JSON has no NaN; the attribute's absence of a value is what it means).
json record_json(const commands::Record& rec, std::size_t max_elements) {
  std::size_t elements = 0;
  for (const auto& a : rec.contents.arrays) elements += a.size();
  for (const auto& d : rec.contents.decimals) elements += d.data->size();
  for (const auto& t : rec.contents.texts) elements += t.data->size();
  if (elements > max_elements)
    throw std::length_error(
        fmt::format("answer: got {} array elements, expected at most {} (the explorer's limit; "
                    "`btob {}` or Python writes larger results)",
                    elements, max_elements, rec.command));
  json j{{"command", rec.command}};
  j["request"] = json::object();
  for (const auto& [name, values] : rec.request) j["request"][name] = values;
  j["attrs"] = json::object();
  for (const auto& [name, value] : rec.attrs) std::visit([&](const auto& v) { j["attrs"][name] = v; }, value);
  j["arrays"] = json::object();
  for (const auto& a : rec.contents.arrays)
    std::visit(
        [&](const auto* v) {
          j["arrays"][a.name] = {{"dims", a.dims}, {"axes", a.axes}, {"units", a.units}, {"data", *v}};
        },
        a.data);
  j["texts"] = json::object();
  for (const auto& t : rec.contents.texts) j["texts"][t.name] = *t.data;
  j["decimals"] = json::object();
  for (const auto& d : rec.contents.decimals) j["decimals"][d.name] = *d.data;
  return j;
}

// The request named by the query: defaults, then the given fields (core::set_field through the scenes' applier); a
// parameter that is no field is an InvalidField naming it and listing the fields.
template <class Req> Req request_of(const Params& p) {
  Req req = commands::Spec<Req>::defaults();
  const Args args = field_args(p);
  std::vector<bool> used(args.size(), false);
  req.fields(detail::ArgsApplier{&args, &used});
  for (std::size_t i = 0; i < args.size(); ++i)
    if (!used[i]) {
      std::string known;
      req.fields(detail::NameLister{&known});
      throw core::InvalidField(args[i].first, "a parameter", "one of command, session, " + known);
    }
  return req;
}

// ready -> compute -> record, as every front end runs a request; the provenance is the command line that
// reproduces it (the query's fields as flags).
template <class Req> std::string run_served(const Params& p, const core::RunControl& control, const Limits& lim) {
  using S = commands::Spec<Req>;
  Req req = request_of<Req>(p);
  commands::ready(req);
  const auto rec = commands::compute(req, commands::How{control});
  std::string line = fmt::format("btob {}", S::command);
  for (const auto& [k, v] : field_args(p)) line += fmt::format(" --{} {}", k, v.front());
  commands::record(*rec, commands::Provenance{line, S::stem_of(req), "", core::thread_count(control.threads)});
  return record_json(*rec, lim.max_answer_elements).dump();
}

// Lists the served commands' names.
struct ServedNames {
  std::vector<std::string>* names;
  template <class Req> void operator()() const {
    if constexpr (commands::Spec<Req>::served) names->push_back(commands::Spec<Req>::command);
  }
};

// Runs the served command called `name`, if this is it.
struct RunIfNamed {
  const std::string* name;
  const Params* p;
  const core::RunControl* control;
  const Limits* lim;
  std::string* out;
  template <class Req> void operator()() const {
    if constexpr (commands::Spec<Req>::served)
      if (*name == commands::Spec<Req>::command) *out = run_served<Req>(*p, *control, *lim);
  }
};
}  // namespace

std::string served_command(const Params& p) {
  std::vector<std::string> names;
  commands::for_each_command(ServedNames{&names});
  const auto it = p.find("command");
  const std::string expected = fmt::format("one of {} (the commands the explorer serves)", fmt::join(names, ", "));
  if (it == p.end()) throw core::InvalidField("command", "nothing", expected);
  if (std::find(names.begin(), names.end(), it->second) == names.end())
    throw core::InvalidField("command", "'" + it->second + "'", expected);
  return it->second;
}

std::string run_json(const Params& p, const core::RunControl& control, const Limits& lim) {
  const std::string name = served_command(p);
  std::string out;
  commands::for_each_command(RunIfNamed{&name, &p, &control, &lim, &out});
  return out;
}

}  // namespace btob::cli::explore
