// SPDX-License-Identifier: GPL-3.0-or-later
// HDF5/CSV/manifest writers with provenance, and the progress bar.
#include "io/io.hpp"
#include "core/cancel.hpp"
#include "io/cancel.hpp"

#include <btob/build_info.hpp>

#include <H5Cpp.h>
#include <fmt/format.h>
#include <signal.h>
#include <spawn.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <sys/wait.h>
#include <thread>

#ifndef BTOB_SOURCE_DIR
#define BTOB_SOURCE_DIR "."
#endif

namespace btob::io {

namespace {
std::string now_utc() {
  const std::time_t t = std::time(nullptr);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}
std::string run_dirty() {
  // Whether analyses/ (scenes, plot scripts, reference tables: read when a result is made, not compiled in) had
  // uncommitted changes when the result was made.  The binary's own state is build::git_dirty, fixed at build time.
  FILE* p = popen("git -C " BTOB_SOURCE_DIR " status --porcelain --untracked-files=no -- analyses 2>/dev/null", "r");
  if (!p) return "unknown";
  char buf[256];
  bool dirty = false;
  while (fgets(buf, sizeof buf, p)) dirty = true;
  return pclose(p) == 0 ? (dirty ? "yes" : "no") : "unknown";
}
double seconds_now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
}  // namespace

Attrs provenance(const std::string& command) {
  return {{"btob_version", std::string(build::version)},
          {"git_commit", std::string(build::git_commit)},
          {"git_dirty", std::string(build::git_dirty)},
          {"run_dirty", run_dirty()},
          {"compiler", std::string(build::compiler)},
          {"build_type", std::string(build::build_type)},
          {"kernel_flags", std::string(build::kernel_flags)},
          {"date_utc", now_utc()},
          {"command", command}};
}

Attrs result_attrs(const std::string& command, const core::Contents& c, const std::string& kind,
                   const std::string& name, const std::string& title, const std::string& scalar, long threads) {
  Attrs a = provenance(command);
  for (const auto& [k, v] : c.attrs) a[k] = v;
  a["kind"] = kind;
  a["name"] = name;
  a["title"] = title;
  a["scalar_type"] = scalar;
  a["threads"] = threads;
  return a;
}

void ensure_dir(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    throw std::runtime_error(fmt::format("out: cannot create directory '{}': {}", dir.string(), ec.message()));
}

struct H5Writer::Impl {
  H5::H5File file;
};

H5Writer::H5Writer(fs::path path) : impl_(nullptr), path_(std::move(path)) {
  tmp_ = path_;
  tmp_ += fmt::format(".tmp-{}", getpid());
  H5::Exception::dontPrint();
  try {
    impl_ = new Impl{H5::H5File(tmp_.string(), H5F_ACC_TRUNC)};
  } catch (const H5::Exception& e) {
    throw std::runtime_error(fmt::format("cannot create HDF5 file '{}': {}", tmp_.string(), e.getDetailMsg()));
  }
}

void init_hdf5() { H5dont_atexit(); }

namespace {
// Destroys an HDF5 object without the C++ API's destructor message on stderr when its close fails (the failure
// has already been reported as one line).
template <class T> void quiet_destroy(T*& object) {
  std::streambuf* old = std::cerr.rdbuf(nullptr);
  delete object;
  object = nullptr;
  std::cerr.rdbuf(old);
}
}  // namespace

H5Writer::~H5Writer() {
  quiet_destroy(impl_);
  if (!committed_) {
    std::error_code ec;
    fs::remove(tmp_, ec);
  }
}

namespace {
// Runs f, turning an HDF5 exception (disk full, permission denied, a vanished folder) into one line naming the file.
template <class F> void h5_guard(const fs::path& path, F&& f) {
  try {
    f();
  } catch (const H5::Exception& e) {
    std::error_code ec;
    const auto space = fs::space(path.parent_path().empty() ? fs::path(".") : path.parent_path(), ec);
    const std::string cause = !ec && space.available < (1u << 20) ? "no space left on the device" : e.getDetailMsg();
    throw std::runtime_error(fmt::format("cannot write '{}': {}", path.string(), cause));
  }
}
}  // namespace

void H5Writer::attrs(const Attrs& a) {
  h5_guard(path_, [&] { write_attrs(a); });
}

void H5Writer::write_attrs(const Attrs& a) {
  H5::Group root = impl_->file.openGroup("/");
  for (const auto& [k, v] : a) {
    H5::DataSpace scalar(H5S_SCALAR);
    if (const auto* s = std::get_if<std::string>(&v)) {
      H5::StrType t(H5::PredType::C_S1, s->empty() ? 1 : s->size());
      root.createAttribute(k, t, scalar).write(t, s->empty() ? std::string(" ") : *s);
    } else if (const auto* d = std::get_if<double>(&v)) {
      root.createAttribute(k, H5::PredType::NATIVE_DOUBLE, scalar).write(H5::PredType::NATIVE_DOUBLE, d);
    } else {
      const long l = std::get<long>(v);
      root.createAttribute(k, H5::PredType::NATIVE_LONG, scalar).write(H5::PredType::NATIVE_LONG, &l);
    }
  }
}

namespace {
template <class V>
void write_ds(H5::H5File& f, const std::string& name, const V& data, const std::vector<std::size_t>& dims,
              const H5::PredType& type) {
  std::vector<hsize_t> d(dims.begin(), dims.end());
  H5::DataSpace space(static_cast<int>(d.size()), d.data());
  H5::DSetCreatPropList plist;
  std::size_t total = 1;
  for (auto x : dims) total *= x;
  if (total >= 4096 && total > 0) {  // chunked + deflate: density images are mostly empty
    std::vector<hsize_t> chunk = d;
    std::size_t c = total;
    for (auto& x : chunk)
      while (c > (1u << 18) && x > 1) {
        c /= 2;
        x = (x + 1) / 2;
      }
    plist.setChunk(static_cast<int>(chunk.size()), chunk.data());
    plist.setDeflate(4);
  }
  H5::DataSet ds = f.createDataSet(name, type, space, plist);
  if (total > 0) ds.write(data.data(), type);
}
}  // namespace

void H5Writer::dataset(const std::string& n, const std::vector<double>& v, const std::vector<std::size_t>& d) {
  h5_guard(path_, [&] { write_ds(impl_->file, n, v, d, H5::PredType::NATIVE_DOUBLE); });
}
void H5Writer::dataset(const std::string& n, const std::vector<std::uint32_t>& v, const std::vector<std::size_t>& d) {
  h5_guard(path_, [&] { write_ds(impl_->file, n, v, d, H5::PredType::NATIVE_UINT32); });
}
void H5Writer::dataset(const std::string& n, const std::vector<std::uint8_t>& v, const std::vector<std::size_t>& d) {
  h5_guard(path_, [&] { write_ds(impl_->file, n, v, d, H5::PredType::NATIVE_UINT8); });
}
void H5Writer::dataset(const std::string& n, const std::vector<std::uint64_t>& v, const std::vector<std::size_t>& d) {
  h5_guard(path_, [&] { write_ds(impl_->file, n, v, d, H5::PredType::NATIVE_UINT64); });
}

void H5Writer::commit() {
  h5_guard(path_, [&] { impl_->file.close(); });
  delete impl_;
  impl_ = nullptr;
  std::error_code ec;
  fs::rename(tmp_, path_, ec);
  if (ec) throw std::runtime_error(fmt::format("cannot move '{}' into place: {}", path_.string(), ec.message()));
  committed_ = true;
}

void write_text_atomic(const fs::path& path, const std::string& text) {
  fs::path tmp = path;
  tmp += fmt::format(".tmp-{}", getpid());
  {
    std::ofstream f(tmp);
    if (f) f << text;
    if (f) f.close();
    if (!f) {
      std::error_code ec;
      fs::remove(tmp, ec);
      throw std::runtime_error(fmt::format("cannot write '{}': {}", path.string(), std::strerror(errno)));
    }
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) throw std::runtime_error(fmt::format("cannot move '{}' into place: {}", path.string(), ec.message()));
}

namespace {
std::string json_escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '"' || c == '\\') o += '\\';
    if (c == '\n') {
      o += "\\n";
      continue;
    }
    o += c;
  }
  return o;
}
}  // namespace

void write_manifest(const fs::path& path, const Attrs& a) {
  std::ostringstream s;
  s << "{\n";
  std::size_t i = 0;
  for (const auto& [k, v] : a) {
    s << "  \"" << json_escape(k) << "\": ";
    if (const auto* str = std::get_if<std::string>(&v)) s << '"' << json_escape(*str) << '"';
    else if (const auto* d = std::get_if<double>(&v))
      s << (std::isfinite(*d) ? fmt::format("{}", *d) : "null");  // JSON has no nan/inf
    else s << std::get<long>(v);
    s << (++i < a.size() ? ",\n" : "\n");
  }
  s << "}\n";
  write_text_atomic(path, s.str());
}

Progress::Progress(std::string label)
    : label_(std::move(label)), tty_(isatty(STDERR_FILENO) != 0), start_(seconds_now()) {}
Progress::~Progress() {
  if (open_) std::cerr << "\n";
}
void Progress::update(std::size_t done, std::size_t total) {
  if (total == 0) return;
  if (!noted_ && done > 0 && done < total) {
    const double el = seconds_now() - start_, left = el * static_cast<double>(total - done) / static_cast<double>(done);
    // A rate from at least 2 s and 1% of the work (or 30 s: a start-up that allocates gigabytes, or a first item
    // that is slower than the rest, would otherwise extrapolate to days); 10 min: worth knowing before waiting.
    const bool rate_known = el >= 2 && (100 * done >= total || el >= 30);
    if (rate_known && left > 600) {
      noted_ = true;
      std::cerr << fmt::format(
                       "{}btob: {}: about {:.0f} min left at the rate so far (--dry-run predicts before a run)\n",
                       open_ ? "\n" : "", label_, left / 60)
                << std::flush;
      open_ = false;
    }
  }
  if (!tty_) return;
  const int p = static_cast<int>(100.0 * static_cast<double>(done) / static_cast<double>(total));
  if (p == last_percent_) return;
  const double el = seconds_now() - start_;
  if (el < 0.5 && p < 100) return;  // short runs stay quiet
  last_percent_ = p;
  const int w = 30, f = w * p / 100;
  // Remaining time at the rate so far (done units in el seconds); padded so that a shorter line covers a longer one.
  const std::string left =
      p < 100 && done > 0
          ? fmt::format(", ~{:.0f}s left   ", el * static_cast<double>(total - done) / static_cast<double>(done))
          : std::string(18, ' ');  // the end: blank what an earlier "left" wrote
  std::cerr << fmt::format("\r{} [{}{}] {:3d}% {:.1f}s{}", label_, std::string(f, '#'), std::string(w - f, '.'), p, el,
                           left);
  open_ = p < 100;  // a finished bar ends its line at once: what the command prints next starts on a new one
  std::cerr << (open_ ? "" : "\n") << std::flush;
}

fs::path data_file(const std::string& rel) {
  std::vector<fs::path> places;
  if (const char* d = std::getenv("BTOB_DATA_DIR"); d && *d) places.push_back(fs::path(d) / rel);
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    places.push_back(exe.parent_path() / "share/btob" / rel);
    places.push_back(exe.parent_path().parent_path() / "share/btob" / rel);
  }
  // The source tree: plot scripts live in analyses/plot, tables in analyses/reference.
  places.push_back(fs::path(BTOB_SOURCE_DIR) / "analyses" / rel);
  std::string tried;
  for (const auto& p : places) {
    if (fs::is_regular_file(p, ec)) return p;
    tried += (tried.empty() ? "" : ", ") + p.string();
  }
  throw std::runtime_error(
      fmt::format("cannot find '{}' (looked in {}); set BTOB_DATA_DIR to the folder holding "
                  "plot/ and reference/",
                  rel, tried));
}

std::string data_text(const std::string& path, const std::string& default_rel) {
  std::ifstream in(path.empty() ? data_file(default_rel) : fs::path(path));
  if (!in) return "";
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

namespace {
const core::CancelToken* stop_token = nullptr;
}  // namespace

void stop_on(const core::CancelToken* token) { stop_token = token; }
void check_stop() { core::check_cancel(stop_token); }

// The plot script runs as a child process (no shell: the arguments are passed as they are).  std::system would
// ignore SIGINT in btob while it waits, so a Ctrl-C during a plot was lost; instead the wait polls the stop token
// every 10 ms and, once it is set, ends the child (SIGTERM) and throws core::Cancelled.
bool run_plot(const std::string& script, const std::vector<std::string>& args) {
  const char* env = std::getenv("BTOB_PYTHON");
  const std::string py = env && *env ? env : "/usr/bin/python3";
  fs::path path;
  try {
    path = data_file("plot/" + script);
  } catch (const std::runtime_error& e) {
    std::cerr << "btob: warning: " << e.what() << "; data were written without the figure\n";
    return false;
  }
  check_stop();
  std::vector<std::string> argv_s{py, path.string()};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawnp(&pid, py.c_str(), nullptr, nullptr, argv.data(), environ) != 0) {
    std::cerr << "btob: warning: plot script " << script << " could not start (" << py
              << "); data were written, run analyses/plot/" << script << " by hand\n";
    return false;
  }
  int status = 0;
  while (waitpid(pid, &status, WNOHANG) == 0) {
    if (stop_token && stop_token->cancelled()) {
      kill(pid, SIGTERM);
      waitpid(pid, &status, 0);
      throw core::Cancelled();
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::cerr << "btob: warning: plot script " << script << " failed (exit "
              << (WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status))
              << "); data were written, run analyses/plot/" << script << " by hand\n";
    return false;
  }
  return true;
}

}  // namespace btob::io
