// SPDX-License-Identifier: GPL-3.0-or-later
// The stages of `btob explore` (explore.hpp): view parsing, the density run, colouring, PNG encoding, and the JSON
// answers of the explorer's own (an orbit's tail, overlays, export); a served command's record is explore_run.cpp's.
#include "cli/explore.hpp"

#include "cli/command.hpp"
#include "commands/execute.hpp"
#include "core/fields.hpp"
#include "extras/extras.hpp"
#include "io/io.hpp"
#include "iterate/kernel.hpp"
#include "iterate/recorders.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <png.h>
#include <zlib.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <mutex>

namespace btob::cli::explore {

namespace {
using nlohmann::json;

const std::string* find(const Params& p, const std::string& name) {
  const auto it = p.find(name);
  return it == p.end() ? nullptr : &it->second;
}
double get_double(const Params& p, const std::string& name, double fallback) {
  const std::string* s = find(p, name);
  return s ? core::parse_double(*s, name) : fallback;
}
long get_long(const Params& p, const std::string& name, long fallback, long lo, long hi) {
  const std::string* s = find(p, name);
  const long v = s ? core::parse_long(*s, name) : fallback;
  if (v < lo || v > hi) throw core::InvalidField(name, std::to_string(v), fmt::format("{}..{}", lo, hi));
  return v;
}
double required_double(const Params& p, const std::string& name, const std::string& expected) {
  const std::string* s = find(p, name);
  if (!s) throw core::InvalidField(name, "nothing", expected);
  return core::parse_double(*s, name);
}

// The view's size and coordinate window.
void parse_frame(const Params& p, const Limits& lim, View& v) {
  v.width = get_long(p, "width", v.width, 1, lim.max_side);
  v.height = get_long(p, "height", v.height, 1, lim.max_side);
  if (const std::string* c = find(p, "coord")) v.coord = *c;
  if (v.coord != "theta" && v.coord != "phi" && v.coord != "log10_theta" && v.coord != "w1" && v.coord != "w2")
    throw core::InvalidField("coord", "'" + v.coord + "'", "theta, phi, log10_theta, w1 or w2");
  const bool lo = find(p, "lo") != nullptr, hi = find(p, "hi") != nullptr;
  if (lo != hi) throw core::InvalidField(lo ? "hi" : "lo", "nothing", "lo and hi together, or neither");
  v.has_range = lo;
  if (lo) {
    v.lo = get_double(p, "lo", 0);
    v.hi = get_double(p, "hi", 0);
    if (!(v.lo < v.hi) || !std::isfinite(v.hi - v.lo))
      throw core::InvalidField("hi", fmt::format("{} with lo = {}", v.hi, v.lo), "finite lo < hi");
  }
}

// The view's work: iterations, tail, initial conditions, within the work budget.
void parse_work(const Params& p, const Limits& lim, View& v) {
  v.iterations = get_long(p, "iterations", v.iterations, 1, 1000000);
  v.tail = get_long(p, "tail", v.tail, 1, v.iterations);
  if (const std::string* g = find(p, "grid")) v.grid = *g;
  const std::size_t orbits = iterate::parse_grid(v.grid, 1, "grid").size();
  const double work = static_cast<double>(v.width) * static_cast<double>(orbits) * static_cast<double>(v.iterations);
  if (work > lim.work_budget)
    throw core::InvalidField(
        "iterations",
        fmt::format("{} x {} orbits x {} columns = {:.3g} map iterations", v.iterations, orbits, v.width, work),
        fmt::format("at most {:.3g} map iterations per image", lim.work_budget));
}
}  // namespace

View parse_view(const Params& p, const Limits& lim) {
  View v;
  v.r_min = required_double(p, "r_min", "a number in (0,1)");
  v.r_max = required_double(p, "r_max", "a number in (0,1)");
  core::require_r(v.r_min, "r_min");
  core::require_r(v.r_max, "r_max");
  if (!(v.r_min < v.r_max))
    throw core::InvalidField("r_max", fmt::format("{}", v.r_max), fmt::format("> r_min = {}", v.r_min));
  parse_frame(p, lim, v);
  parse_work(p, lim, v);
  if (const std::string* o = find(p, "overlay")) {
    for (std::size_t a = 0; a < o->size();) {
      const std::size_t b = std::min(o->find(',', a), o->size());
      if (b > a) v.overlay.push_back(o->substr(a, b - a));
      a = b + 1;
    }
    extras::check_overlays(v.overlay);
  }
  to_request(v).validate();  // what the bifurcation request checks besides (the grid's memory, the precision)
  return v;
}

bifurcation::Request to_request(const View& v) {
  bifurcation::Request r;
  r.r_min = v.r_min;
  r.r_max = v.r_max;
  r.r_count = v.width;
  r.bins = v.height;
  r.iterations = v.iterations;
  r.tail = v.tail;
  r.log = v.coord == "log10_theta";
  r.coord = r.log ? "theta" : v.coord;
  if (v.has_range) r.range = {v.lo, v.hi};
  r.grid = v.grid;
  r.overlay = v.overlay;
  return r;
}

// The view's request through the commands' one path (commands/execute.hpp: ready, then run; the overlays are the
// page's own, /api/overlays).
bifurcation::Result compute(const View& v, const core::RunControl& control) {
  bifurcation::Request req = to_request(v);
  commands::ready(req);
  return std::move(*commands::run_request(req, commands::How{control}));
}

const std::vector<std::uint8_t>& palette() {
  // Background white; then from light orange through orange and crimson to near-black violet: dark is dense, as in
  // the paper's figures, and neighbouring counts stay distinguishable on a log scale.
  static const std::vector<std::uint8_t> pal = [] {
    const double stops[5][3] = {{244, 178, 80}, {228, 106, 48}, {186, 40, 70}, {98, 20, 100}, {18, 8, 38}};
    std::vector<std::uint8_t> p(256 * 3, 255);
    for (int i = 1; i < 256; ++i) {
      const double t = (i - 1) / 254.0 * 4;
      const int s = std::min(3, static_cast<int>(t));
      const double f = t - s;
      for (int c = 0; c < 3; ++c)
        p[static_cast<std::size_t>(3 * i + c)] =
            static_cast<std::uint8_t>(std::lround(stops[s][c] + f * (stops[s + 1][c] - stops[s][c])));
    }
    return p;
  }();
  return pal;
}

Image colour(const bifurcation::Result& res) {
  Image img;
  img.width = static_cast<long>(res.ensemble.r.size());
  img.height = static_cast<long>(res.bins);
  img.pixels.assign(static_cast<std::size_t>(img.width * img.height), 0);
  std::uint32_t top = 0;
  for (std::uint32_t c : res.density) top = std::max(top, c);
  if (top == 0) return img;
  const double scale = 254.0 / std::log1p(static_cast<double>(top));
  const auto index = [scale](std::uint32_t c) {
    return static_cast<std::uint8_t>(1 + std::lround(scale * std::log1p(static_cast<double>(c))));
  };
  // The index of every count up to 4096 once (a column's counts are mostly small); larger ones computed each time.
  std::vector<std::uint8_t> table(std::min<std::size_t>(top, 4096) + 1, 0);
  for (std::size_t c = 1; c < table.size(); ++c) table[c] = index(static_cast<std::uint32_t>(c));
  const std::size_t W = static_cast<std::size_t>(img.width), H = static_cast<std::size_t>(img.height);
  for (std::size_t col = 0; col < W; ++col) {
    const std::uint32_t* counts = res.density.data() + col * H;  // density is [r, bin], bin 0 at lo
    for (std::size_t b = 0; b < H; ++b)
      if (counts[b]) img.pixels[(H - 1 - b) * W + col] = counts[b] < table.size() ? table[counts[b]] : index(counts[b]);
  }
  return img;
}

namespace {
struct PngSink {
  std::string* out;
  char message[256];
};
extern "C" void png_append(png_structp png, png_bytep data, png_size_t n) {
  static_cast<PngSink*>(png_get_io_ptr(png))->out->append(reinterpret_cast<const char*>(data), n);
}
extern "C" void png_fail(png_structp png, png_const_charp msg) {
  PngSink* sink = static_cast<PngSink*>(png_get_error_ptr(png));
  std::snprintf(sink->message, sizeof sink->message, "%s", msg);
  png_longjmp(png, 1);
}
// libpng's write sequence; returns false on an error (sink.message says which).  No C++ object lives in this frame
// across setjmp, so libpng's longjmp skips no destructor.
bool write_png(png_structp png, png_infop info, const Image& img, bool fast) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_IHDR(png, info, static_cast<png_uint_32>(img.width), static_cast<png_uint_32>(img.height), 8,
               PNG_COLOR_TYPE_PALETTE, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_color colours[256];
  for (int i = 0; i < 256; ++i)
    colours[i] = {palette()[static_cast<std::size_t>(3 * i)], palette()[static_cast<std::size_t>(3 * i + 1)],
                  palette()[static_cast<std::size_t>(3 * i + 2)]};
  png_set_PLTE(png, info, colours, 256);
  png_set_filter(png, 0, PNG_FILTER_NONE);  // indices: no filter predicts them better (libpng's own advice)
  // Live views: zlib level 1 with run-length matches only (an image is mostly runs of empty bins) costs a few ms;
  // exports: the default level, a smaller file.
  png_set_compression_level(png, fast ? 1 : 6);
  if (fast) png_set_compression_strategy(png, Z_RLE);
  png_write_info(png, info);
  for (long y = 0; y < img.height; ++y) png_write_row(png, img.pixels.data() + static_cast<std::size_t>(y * img.width));
  png_write_end(png, info);
  return true;
}
}  // namespace

std::string encode_png(const Image& img, bool fast) {
  std::string out;
  PngSink sink{&out, {0}};
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &sink, png_fail, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    throw std::runtime_error("PNG encoding: out of memory");
  }
  png_set_write_fn(png, &sink, png_append, nullptr);
  const bool ok = write_png(png, info, img, fast);
  png_destroy_write_struct(&png, &info);
  if (!ok) throw std::runtime_error(std::string("PNG encoding failed: ") + sink.message);
  return out;
}

std::string error_json(const std::string& message) { return json{{"error", message}}.dump(); }

namespace {
// The last `tail` points of the orbit of u0 at r in the strip (w1, w2), after `transient` steps.
std::pair<std::vector<double>, std::vector<double>> strip_tail(double r, const core::Vec3<double>& u0, long transient,
                                                               long tail, const core::RunControl& control) {
  iterate::Ensemble e;
  e.r = {r};
  e.initial = {u0};
  iterate::TailRecorder w1(iterate::Coord::w1, 1, transient + tail, tail),
      w2(iterate::Coord::w2, 1, transient + tail, tail);
  iterate::Both<iterate::TailRecorder, iterate::TailRecorder> both(w1, w2);
  iterate::RunOptions opt;
  opt.threads = 1;
  opt.cancel = control.cancel;
  iterate::run<double>(e, transient + tail, both, opt);
  return {std::move(w1.out), std::move(w2.out)};
}
}  // namespace

std::string tail_json(const Params& p, const core::RunControl& control) {
  const double r = required_double(p, "r", "a value in the open interval (0, 1)");
  core::require_r(r, "r");
  const std::string* point = find(p, "point");
  if (!point) throw core::InvalidField("point", "nothing", "an initial direction x,y,z with x z <= 0");
  const core::Vec3<double> u0 = core::parse_point(*point, "point");
  // The classifier's transients run up to 1e7 steps; one orbit of 1e7 steps is a fraction of a second.
  const long transient = get_long(p, "transient", 0, 0, 10000000), tail = get_long(p, "tail", 300, 1, 100000);
  const auto [w1, w2] = strip_tail(r, u0, transient, tail, control);
  return json{{"w1", w1}, {"w2", w2}}.dump();
}

std::string overlays_json(const Params& p) {
  const double r_min = required_double(p, "r_min", "a number in (0,1)"),
               r_max = required_double(p, "r_max", "a number in (0,1)");
  core::require_r(r_min, "r_min");
  core::require_r(r_max, "r_max");
  json j;
  // The windows overlay gives the lower bounds (colour 1) and r_crit,2 (colour 0) of every window inside.
  const std::vector<double> win = extras::overlay_values({"windows"}, r_min, r_max);
  j["window_bounds"] = json::array();
  j["r_crit2"] = json::array();
  for (std::size_t i = 0; i + 1 < win.size(); i += 2)
    (win[i + 1] == 1 ? j["window_bounds"] : j["r_crit2"]).push_back(win[i]);
  for (const char* kind : {"thresholds", "stripes"}) {
    const std::vector<double> lines = extras::overlay_values({kind}, r_min, r_max);
    j[kind] = json::array();
    for (std::size_t i = 0; i < lines.size(); i += 2) j[kind].push_back(lines[i]);
  }
  return j.dump();
}

namespace {
// The scene of a view: every field of its bifurcation request as a TOML string (the text each field reads back
// bitwise, as a manifest records it), booleans bare.
std::string scene_text(const View& v, const std::string& stem) {
  Args args;
  bifurcation::Request req = to_request(v);
  req.fields(core::ArgsWriter{&args});
  std::string s = fmt::format("# A view of `btob explore`; `btob run {}.toml` computes its density again.\n", stem);
  s += "command = \"bifurcation\"\n";
  s += fmt::format("title = {}\n",
                   json(fmt::format("explore: {} over r in [{}, {}]", v.coord, v.r_min, v.r_max)).dump());
  s += "[args]\n";
  for (const auto& [key, vals] : args) {
    if (vals.empty()) continue;
    if (vals.size() == 1 && (vals[0] == "true" || vals[0] == "false")) {
      s += fmt::format("{} = {}\n", key, vals[0]);
    } else if (vals.size() == 1 && key != "range" && key != "vline" && key != "overlay") {
      s += fmt::format("{} = {}\n", key, json(vals[0]).dump());
    } else {
      s += fmt::format("{} = {}\n", key, json(vals).dump());
    }
  }
  return s;
}

// The first free stem view-K in `dir` (a process-wide counter, so two exports never take the same one).
std::string free_stem(const std::filesystem::path& dir) {
  static std::atomic<int> next{1};
  static std::mutex m;
  std::lock_guard<std::mutex> lock(m);
  for (;; ++next) {
    const std::string stem = fmt::format("view-{}", next.load());
    if (!std::filesystem::exists(dir / (stem + ".toml")) && !std::filesystem::exists(dir / (stem + ".png"))) {
      ++next;
      return stem;
    }
  }
}
}  // namespace

std::string export_view(const View& v, const std::filesystem::path& dir) {
  const bifurcation::Result res = compute(v, {});
  const std::string png = encode_png(colour(res), false);
  std::filesystem::create_directories(dir);
  const std::string stem = free_stem(dir);
  io::write_text_atomic(dir / (stem + ".png"), png);
  io::write_text_atomic(dir / (stem + ".toml"), scene_text(v, stem));
  std::uint64_t points = 0;
  for (std::uint32_t c : res.density) points += c;
  return json{{"scene", stem + ".toml"}, {"png", stem + ".png"}, {"folder", dir.string()}, {"points_in_range", points}}
      .dump();
}

}  // namespace btob::cli::explore
