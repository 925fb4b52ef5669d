// Shared helpers of the subcommands, and the built-in "thresholds" overlay.
#include "cli/common.hpp"
#include "cli/app.hpp"

#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <memory>

namespace btob::cli {

std::string& invocation() {
  static std::string s;
  return s;
}

ProgressAdapter& progress_adapter(io::Progress& p) {
  thread_local std::unique_ptr<ProgressAdapter> a;
  a = std::make_unique<ProgressAdapter>(&p);
  return *a;
}

io::fs::file_time_type start_time() {
  return io::fs::file_time_type::clock::now() - std::chrono::milliseconds(50);
}

void print_written(const std::vector<io::fs::path>& files, io::fs::file_time_type since) {
  std::string s;
  for (const auto& f : files) {
    std::error_code ec;
    const auto t = io::fs::last_write_time(f, ec);
    if (!ec && t >= since) s += (s.empty() ? "" : ", ") + f.string();
  }
  if (!s.empty()) std::cerr << "btob: wrote " << s << "\n";
}

std::map<std::string, OverlayFn>& overlays() {
  static std::map<std::string, OverlayFn> m;
  return m;
}

std::string overlay_names() {
  std::string s;
  for (const auto& [k, v] : overlays()) s += (s.empty() ? "" : ", ") + k;
  return s;
}

std::vector<double> overlay_values(const std::vector<std::string>& names, double r_min, double r_max) {
  std::vector<double> out;
  for (const auto& n : names) {
    auto it = overlays().find(n);
    if (it == overlays().end())
      throw UsageError(fmt::format("overlay: got '{}', expected one of {}", n, overlay_names()));
    for (const auto& [r, colour] : it->second(r_min, r_max))
      if (r >= r_min && r <= r_max) {
        out.push_back(r);
        out.push_back(colour);
      }
  }
  return out;
}

namespace {
// Constants quoted in the paper (Sections 1, 4, 5): three-particle collapse 7-4*sqrt(3), end of the
// (ab)^2(cb)^2 window 3-2*sqrt(2), end of the (ab)^3(cb)^3 window 5-2*sqrt(6), no four-particle
// collapse above 2^(2/3)-1.
RegisterOverlay thresholds("thresholds", [](double, double) {
  return std::vector<std::pair<double, int>>{{7 - 4 * std::sqrt(3.0), 0},
                                             {3 - 2 * std::sqrt(2.0), 0},
                                             {5 - 2 * std::sqrt(6.0), 0},
                                             {std::cbrt(4.0) - 1, 0}};
});
}  // namespace

}  // namespace btob::cli
