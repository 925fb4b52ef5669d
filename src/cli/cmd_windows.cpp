// SPDX-License-Identifier: GPL-3.0-or-later
// `btob windows poly|bounds|thresholds|stripes|verify|precision`: flags -> windows::*Request -> run -> stdout or
// files.  poly, bounds, verify and precision are sweeps over n (cli/sweep.hpp): under mpirun the ranks share the n
// values and rank 0 prints or writes.
#include "cli/app.hpp"
#include "cli/command.hpp"
#include "cli/common.hpp"
#include "cli/sweep.hpp"
#include "extras/extras.hpp"
#include "windows/requests.hpp"

#include <fmt/format.h>

#include <iostream>

namespace btob::cli {
namespace {

// sweep() with a progress bar on standard error (rank 0 only: the others are quiet): the result on rank 0.
template <class Req>
auto sweep_with_progress(const Req& req, const Output& o, const Context& ctx, const std::string& label) {
  Context run_ctx = ctx;
  const auto bar = terminal_progress(label);
  if (!o.quiet) run_ctx.control.progress = bar.get();
  return sweep(req, run_ctx);
}

void bounds(const windows::BoundsRequest& req, const Output& o, const Context& ctx) {
  const auto got = sweep_with_progress(req, o, ctx, "windows bounds");
  if (!got) return;
  const windows::BoundsResult& res = *got;
  std::cout << res.csv() << std::flush;
  for (const auto& c : res.certificates)
    if (!c.valid()) std::cerr << fmt::format("btob: warning: certificate of n = {} failed\n", c.n);
}

void verify(const windows::VerifyRequest& req, const Output& o, const Context& ctx) {
  const auto got = sweep_with_progress(req, o, ctx, "windows verify");
  if (!got) return;
  const windows::VerifyResult& res = *got;
  core::Contents c;
  res.describe(c);
  // The stem: --name, else verify for the committed n = 2..125 and verify_A-B otherwise (default_name()).
  io::Attrs at = ctx.attrs(o, c, "windows_verify", req.precision);
  io::ResultFiles files(o.out, o.name);
  files.tables(res.tables());
  files.h5(c, at);
  ctx.manifest(files, at);
  files.commit();
  std::cout << fmt::format("windows verify n = {}..{}: {} of {} checks pass ({:.1f} s); wrote {}\n", res.range.first,
                           res.range.last, res.passed, res.total, res.total_seconds,
                           files.final_path(o.name + ".csv").string());
}

void precision(const windows::BoundPrecisionRequest& req, const Output& o, const Context& ctx) {
  const auto got = sweep_with_progress(req, o, ctx, "windows precision");
  if (!got) return;
  const windows::BoundPrecisionResult& res = *got;
  core::Contents c;
  res.describe(c);
  io::Attrs at =
      ctx.attrs(o, c, "windows_precision", fmt::format("float,double,long-double,float128,mpfr:{}", req.mpfr_digits));
  extras::of(req).apply(at);  // threads = 1: the study runs on one thread
  io::ResultFiles files(o.out, o.name);
  files.tables(res.tables());
  files.h5(c, at);
  ctx.manifest(files, at);
  if (!o.no_plot) files.plot("windows_precision.py");  // the script reads NAME.h5 alone
  files.commit();
  std::cout << res.summary_csv();
}

// `btob windows` itself: only a parent of the subcommands below (registered first, so they find it).
Register parent([](CLI::App& app) {
  app.add_subcommand("windows", "Windows of stability of (ab)^n(cb)^n: Q_n, bounds, checks (Section 4, App. B)")
      ->require_subcommand(1);
});

struct Registration {
  Registration() {
    command<windows::PolyRequest>(
        "windows poly", "Q_n = r^2n P_n(r) P_n(1/r) - r^2n exactly, developed and factorised (Table B.2)",
        Output::to_stdout(), [](const windows::PolyRequest& req, const Output&, const Context& ctx) {
          if (const auto res = sweep(req, ctx)) std::cout << res->text();
        });
    command<windows::BoundsRequest>("windows bounds",
                                    "CSV n,lower_bound,upper_bound (Table B.1); --certify adds exact certificates",
                                    Output::to_stdout(), bounds);
    command<windows::ThresholdsRequest>(
        "windows thresholds", "7-4sqrt3, 3-2sqrt2, 5-2sqrt6, 2^(2/3)-1 in high precision", Output::to_stdout(),
        [](const windows::ThresholdsRequest& req, const Output&, const Context& ctx) {
          std::cout << windows::run(req, ctx.control).csv();
        });
    command<windows::StripesRequest>("windows stripes", "thin stripes r(l/m), eq. (6.3), 1/4 < l/m <= 1/2, m <= max-m",
                                     Output::to_stdout(),
                                     [](const windows::StripesRequest& req, const Output&, const Context& ctx) {
                                       std::cout << windows::run(req, ctx.control).csv();
                                     });
    command<windows::VerifyRequest>(
        "windows verify",
        "iterate the Section 4 grid inside/below each window; CSV + manifest (file stem verify for n = 2..125, else "
        "verify_A-B, unless --name is given)",
        Output{"results/windows", "", "", 0, false, false}, verify);
    command<windows::BoundPrecisionRequest>("windows precision",
                                            "largest n with a 12-decimal bound per precision and route; CSV + PNG",
                                            Output{"results/windows", "precision", "", 0, false, false}, precision);
  }
} registration;

}  // namespace
}  // namespace btob::cli
