// SPDX-License-Identifier: GPL-3.0-or-later
// The route rates and their cache file (io/rates.hpp).
#include "io/rates.hpp"

#include "core/cancel.hpp"
#include "core/run.hpp"
#include "core/size_model.hpp"

#include <btob/build_info.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <system_error>

namespace btob::io {
namespace fs = std::filesystem;
namespace {

// The format tag a cache file must carry; a file without it (foreign, older) is replaced, not read.
constexpr const char* cache_format = "btob route rates 1";
// One probe's duration: long enough that timer resolution and a cold cache are small against it, short enough that a
// first run hardly notices its calibration.
constexpr double probe_target_seconds = 0.1;

std::string cpu_model() {
  std::ifstream f("/proc/cpuinfo");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(' ', colon + 1));
    }
  return "unknown cpu";
}

// The cache's rates by key; empty when the file is missing, unreadable, not JSON or of another format.
nlohmann::json load_rates(const fs::path& path) {
  std::ifstream f(path);
  if (!f) return nlohmann::json::object();
  const nlohmann::json j = nlohmann::json::parse(f, nullptr, false);
  if (j.is_discarded() || !j.is_object() || j.value("format", std::string()) != cache_format || !j.contains("rates") ||
      !j["rates"].is_object())
    return nlohmann::json::object();
  return j["rates"];
}

// Adds `key` to the file's rates (read again, so entries another process added meanwhile are kept) and rewrites the
// file through a temporary renamed into place.  Every failure (no directory, read-only, full disk) is ignored.
void store_rate(const fs::path& path, const std::string& key, const RouteRate& r) {
  if (path.empty()) return;
  std::error_code ec;
  fs::create_directories(path.parent_path(), ec);
  nlohmann::json rates = load_rates(path);
  rates[key] = {
      {"units_per_second", r.units_per_second}, {"probe_units", r.probe_units}, {"probe_seconds", r.probe_seconds}};
  const nlohmann::json j = {{"format", cache_format}, {"rates", rates}};
  fs::path tmp = path;
  tmp += fmt::format(".tmp-{}", getpid());
  {
    std::ofstream f(tmp);
    if (f) f << j.dump(1) << "\n";
    if (f) f.close();
    if (!f) {
      fs::remove(tmp, ec);
      return;
    }
  }
  fs::rename(tmp, path, ec);
  if (ec) fs::remove(tmp, ec);
}

// A cached entry, when it holds a positive finite rate.
bool cached_rate(const nlohmann::json& rates, const std::string& key, RouteRate& out) {
  if (!rates.contains(key) || !rates[key].is_object()) return false;
  const auto& e = rates[key];
  const auto num = [&](const char* k) { return e.contains(k) && e[k].is_number() ? e[k].get<double>() : -1.0; };
  out.units_per_second = num("units_per_second");
  out.probe_units = num("probe_units");
  out.probe_seconds = num("probe_seconds");
  out.cached = true;
  return std::isfinite(out.units_per_second) && out.units_per_second > 0;
}

// Times the probe, growing n (x8 while a probe is short, then towards the target) until one probe takes 0.1 s.
RouteRate calibrate(const core::Term& term, const core::RunControl& control) {
  RouteRate r;
  double n = 16;
  for (;;) {
    core::check_cancel(control.cancel);
    const auto t0 = std::chrono::steady_clock::now();
    const double done = term.probe(n, control);
    const double dt = core::seconds_since(t0);
    r.probe_units = done, r.probe_seconds = dt;
    if (dt >= probe_target_seconds || n >= 1e15) break;
    n *= dt <= probe_target_seconds / 8 ? 8 : std::max(1.25, 1.2 * probe_target_seconds / dt);
  }
  r.units_per_second = r.probe_units / std::max(r.probe_seconds, 1e-9);
  return r;
}

std::string size_text(double bytes) {
  if (bytes < 1e3) return fmt::format("{:.0f} B", bytes);
  if (bytes < 1e6) return fmt::format("{:.3g} kB", bytes / 1e3);
  if (bytes < 1e9) return fmt::format("{:.3g} MB", bytes / 1e6);
  return fmt::format("{:.3g} GB", bytes / 1e9);
}

std::string time_text(double s) {
  if (s < 120) return fmt::format("{:.3g} s", s);
  if (s < 7200) return fmt::format("{:.3g} s (about {:.0f} min)", s, s / 60);
  return fmt::format("{:.3g} s (about {:.1f} h)", s, s / 3600);
}

// A sized term's time from instances of small sizes (core/size_model.hpp): units per second = units / the time
// predicted at the request's size.
RouteRate fitted_rate(const core::Term& term, const core::RunControl& control, int threads) {
  core::RunControl c = control;
  c.threads = threads;
  c.progress = nullptr;
  // The request's work first, outside the instances' timing (counting it may take a few tenths of a second).
  const double w_req = term.work_of ? term.work_of(term.size) : 0;
  const core::SizeFit f = core::fit_sizes(
      term.size_parameter, term.smallest, term.size, [&](double s) { term.sized_run(s, c); }, control.cancel);
  RouteRate r;
  r.units_per_second = term.units / std::max(f.at(term.size), 1e-9);
  r.probe_units = static_cast<double>(f.sizes.size());
  r.probe_seconds = f.spent;
  r.model = f.note(term.size);
  if (term.work_of && !f.sizes.empty()) {  // proportional to the counted work, from the largest instance timed
    const double w_last = term.work_of(f.sizes.back());
    const double w = f.sizes.back() >= term.size ? w_last : w_req;  // the request itself timed: its own count
    if (w > 0 && w_last > 0) {
      r.units_per_second = term.units / std::max(f.seconds.back() * w / w_last, 1e-9);
      r.model = fmt::format(
          "{} from sizes {:.0f}..{:.0f} of {} ({} instances timed in {:.2f} s), in proportion to "
          "the counted work ({:.4g} against {:.4g} of the largest instance timed)",
          f.extrapolates(term.size) ? "extrapolated" : "interpolated", f.sizes.front(), f.sizes.back(),
          term.size_parameter, f.sizes.size(), f.spent, w, w_last);
    }
  }
  return r;
}

}  // namespace

fs::path rates_path() {
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return fs::path(x) / "btob" / "rates.json";
  if (const char* h = std::getenv("HOME"); h && *h) return fs::path(h) / ".cache" / "btob" / "rates.json";
  return {};
}

std::string rate_key(const std::string& route, int threads) {
  static const std::string cpu = cpu_model();
  return fmt::format("btob {} {} | {} | {} threads | {}", build::version, build::git_commit, cpu, threads, route);
}

RouteRate route_rate(const core::Term& term, const core::RunControl& control, int threads) {
  const fs::path path = rates_path();
  const std::string key = rate_key(term.route, threads);
  RouteRate r;
  if (!path.empty() && cached_rate(load_rates(path), key, r)) return r;
  core::RunControl c = control;
  c.threads = threads;
  c.progress = nullptr;
  r = calibrate(term, c);
  store_rate(path, key, r);
  return r;
}

void remember_rate(const core::Term& term, int threads, double units, double seconds) {
  if (!(units > 0 && seconds > 0)) return;
  RouteRate r;
  r.units_per_second = units / seconds;
  r.probe_units = units, r.probe_seconds = seconds;
  store_rate(rates_path(), rate_key(term.route, threads), r);
}

WorkEstimate estimate_work(core::Work work, const core::RunControl& control, int threads) {
  WorkEstimate e;
  e.threads = threads;
  for (const core::Term& t : work.terms) {
    // Two terms of one route share its rate (and its probe runs once).
    auto same =
        std::find_if(work.terms.begin(), work.terms.end(), [&](const core::Term& u) { return u.route == t.route; });
    const auto k = static_cast<std::size_t>(same - work.terms.begin());
    e.rates.push_back(k < e.rates.size() ? e.rates[k]
                      : t.sized_run      ? fitted_rate(t, control, threads)
                                         : route_rate(t, control, threads));
    e.predicted_seconds += t.units / e.rates.back().units_per_second;
  }
  e.work = std::move(work);
  return e;
}

std::string WorkEstimate::text(const std::string& command, bool dry_run) const {
  std::ostringstream s;
  if (dry_run)
    s << fmt::format(
        "btob {}: dry run (only the probes of routes not yet calibrated, or small instances of a sized request, run; "
        "nothing written)\n",
        command);
  else s << fmt::format("btob {}: a long run; its estimate first (--dry-run prints it without running)\n", command);
  for (std::size_t i = 0; i < work.terms.size(); ++i) {
    const core::Term& t = work.terms[i];
    const RouteRate& r = rates[i];
    s << fmt::format("  work: {:.4g} {}\n", t.units, t.what);
    if (!r.model.empty()) {
      s << fmt::format("    model: {}\n", r.model);
      continue;
    }
    s << fmt::format("    rate: {:.4g} per s on {} thread{} (route '{}', {} a probe of {:.4g} in {:.3f} s)\n",
                     r.units_per_second, threads, threads == 1 ? "" : "s", t.route,
                     r.cached ? "cached from" : "calibrated now by", r.probe_units, r.probe_seconds);
  }
  s << fmt::format("  predicted: {} on {} thread{}{}\n", time_text(predicted_seconds), threads, threads == 1 ? "" : "s",
                   work.bound.empty() ? "" : " at most (an upper bound: " + work.bound + ")");
  s << fmt::format("  output: about {} of data (figures not counted); peak memory about {} (the run's data)\n",
                   size_text(work.output_bytes), size_text(work.peak_bytes));
  const fs::path p = rates_path();
  s << "  rates: " << (p.empty() ? "not cached (neither XDG_CACHE_HOME nor HOME is set)" : "cached in " + p.string())
    << "\n"
    << (dry_run ? "  nothing written (no result file, no output)\n" : "");
  return s.str();
}

}  // namespace btob::io
