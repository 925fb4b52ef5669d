// SPDX-License-Identifier: GPL-3.0-or-later
// `btob explore`: an HTTP server (cpp-httplib) for the page of src/cli/explore/ (embedded in the executable at
// build time) and its API (explore.hpp computes the answers).  Loopback only unless --host says otherwise.  A request
// carrying session=S cancels the computation of the same kind still running for S: the page's newest view wins.
#include "cli/app.hpp"
#include "cli/command.hpp"
#include "cli/explore.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <httplib.h>
#include <mpfr.h>
#include <nlohmann/json.hpp>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <mutex>
#include <set>
#include <thread>

extern char** environ;

namespace btob::cli::explore {
// The page's files, embedded at build time (cmake/EmbedAssets.cmake writes explore_assets.cpp).
struct Asset {
  const unsigned char* data;
  std::size_t size;
  const char* mime;
};
const std::map<std::string, Asset>& assets();
}  // namespace btob::cli::explore

namespace btob::cli {
namespace {
namespace ex = explore;
using nlohmann::json;

// A computation in flight: its cancellation token and its progress (polled by GET /api/progress).
struct Job : core::ProgressSink {
  core::CancelToken token;
  std::atomic<std::size_t> done{0}, total{0};
  void update(std::size_t d, std::size_t t) override {
    done.store(d, std::memory_order_relaxed);
    total.store(t, std::memory_order_relaxed);
  }
};

// The running job of each (session, kind); a new one cancels its predecessor.
class Jobs {
 public:
  std::shared_ptr<Job> start(const std::string& session, const std::string& kind) {
    auto job = std::make_shared<Job>();
    if (session.empty()) return job;  // no session: nothing to replace, nothing to poll
    std::lock_guard<std::mutex> lock(m_);
    auto& slot = running_[session + "/" + kind];
    if (slot) slot->token.cancel();
    slot = job;
    return job;
  }
  void finish(const std::string& session, const std::string& kind, const std::shared_ptr<Job>& job) {
    std::lock_guard<std::mutex> lock(m_);
    const auto it = running_.find(session + "/" + kind);
    if (it != running_.end() && it->second == job) running_.erase(it);
  }
  json progress(const std::string& session) {
    std::lock_guard<std::mutex> lock(m_);
    json j = json::object();
    for (const auto& [key, job] : running_)
      if (key.starts_with(session + "/"))
        j[key.substr(session.size() + 1)] = {{"done", job->done.load()}, {"total", job->total.load()}};
    return j;
  }
  void cancel_all() {
    std::lock_guard<std::mutex> lock(m_);
    for (auto& [key, job] : running_) job->token.cancel();
  }

 private:
  std::mutex m_;
  std::map<std::string, std::shared_ptr<Job>> running_;
};

struct Settings {
  std::string host = "127.0.0.1";
  int port = 8765;
  bool no_browser = false;
  std::string export_dir = "explore-exports";
  int threads = 0;
};

// The query's parameters (the first value of each name), the session's name checked.
ex::Params query_of(const httplib::Request& req) {
  ex::Params p;
  for (const auto& [k, v] : req.params) p.emplace(k, v);
  const auto s = p.find("session");
  if (s != p.end() && (s->second.size() > 64 ||
                       s->second.find_first_not_of(
                           "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_") != std::string::npos))
    throw core::InvalidField("session", "'" + s->second.substr(0, 64) + "'", "up to 64 letters, digits, - or _");
  return p;
}

// The query's parameters, any name outside `known` an error naming the known ones.
ex::Params params_of(const httplib::Request& req, std::initializer_list<const char*> known) {
  ex::Params p = query_of(req);
  for (const auto& [k, v] : p)
    if (std::find_if(known.begin(), known.end(), [&](const char* n) { return k == n; }) == known.end()) {
      std::string names;
      for (const char* n : known) names += (names.empty() ? "" : ", ") + std::string(n);
      throw core::InvalidField(k, "a parameter", "one of " + names);
    }
  return p;
}

// Runs `f` (which fills `res`), answering errors as one-line JSON: 400 for a bad request, 409 for a computation a
// newer one cancelled, 500 otherwise.  The server keeps serving in every case.
template <class F> void answer(httplib::Response& res, F&& f) {
  const auto fail = [&](int status, const std::string& what) {
    res.status = status;
    res.set_content(ex::error_json(what), "application/json");
  };
  try {
    f();
  } catch (const core::Cancelled&) {
    fail(409, "cancelled: a newer request of this session replaced it");
  } catch (const std::invalid_argument& e) {  // core::InvalidField among them
    fail(400, e.what());
  } catch (const std::length_error& e) {  // iterate::checked_bytes: more memory than a request may take
    fail(400, e.what());
  } catch (const std::domain_error& e) {
    fail(400, e.what());
  } catch (const std::bad_alloc&) {
    fail(503, "out of memory");
  } catch (const std::exception& e) {
    fail(500, e.what());
  }
}

// A computation of `kind` for the request's session: its control (threads, progress, cancellation) for `f`.
template <class F> void with_job(Jobs& jobs, const Settings& s, const ex::Params& p, const std::string& kind, F&& f) {
  const auto it = p.find("session");
  const std::string session = it == p.end() ? "" : it->second;
  const std::shared_ptr<Job> job = jobs.start(session, kind);
  core::RunControl control;
  control.threads = s.threads;
  control.cancel = &job->token;
  control.progress = job.get();
  try {
    f(control);
  } catch (...) {
    jobs.finish(session, kind, job);
    throw;
  }
  jobs.finish(session, kind, job);
}

double ms_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

// GET /api/bifurcation: parse -> compute -> colour -> encode, each stage timed in the Server-Timing header.
void bifurcation_png(Jobs& jobs, const Settings& s, const httplib::Request& req, httplib::Response& res) {
  const ex::Params p = params_of(
      req, {"r_min", "r_max", "coord", "lo", "hi", "width", "height", "iterations", "tail", "grid", "session"});
  const ex::View view = ex::parse_view(p);
  with_job(jobs, s, p, "bifurcation", [&](const core::RunControl& control) {
    auto t = std::chrono::steady_clock::now();
    const bifurcation::Result r = ex::compute(view, control);
    const double t_compute = ms_since(t);
    t = std::chrono::steady_clock::now();
    const ex::Image img = ex::colour(r);
    const double t_colour = ms_since(t);
    t = std::chrono::steady_clock::now();
    const std::string png = ex::encode_png(img, true);
    const double t_png = ms_since(t);
    // compute = iterate (the kernel with its density recorder) + the request's setup and the per-thread images' merge
    res.set_header("Server-Timing",
                   fmt::format("compute;dur={:.2f}, iterate;dur={:.2f}, colour;dur={:.2f}, png;dur={:.2f}", t_compute,
                               1e3 * r.iteration_seconds, t_colour, t_png));
    res.set_header("X-Btob-Orbits", std::to_string(r.ensemble.orbits()));
    res.set_header("X-Btob-Iterations", std::to_string(view.iterations));
    res.set_header("Cache-Control", "no-store");
    res.set_content(png, "image/png");
  });
}

void json_reply(httplib::Response& res, const std::string& body) {
  res.set_header("Cache-Control", "no-store");
  res.set_content(body, "application/json");
}

void api_routes(httplib::Server& svr, Jobs& jobs, const Settings& s) {
  svr.Get("/api/bifurcation", [&](const httplib::Request& req, httplib::Response& res) {
    answer(res, [&] { bifurcation_png(jobs, s, req, res); });
  });
  // A served command of the registry, its fields by their flag names (explore_run.cpp); its session's job is the
  // command's name, so that /api/progress reports it under that name.
  svr.Get("/api/run", [&](const httplib::Request& req, httplib::Response& res) {
    answer(res, [&] {
      const ex::Params p = query_of(req);
      with_job(jobs, s, p, ex::served_command(p),
               [&](const core::RunControl& c) { json_reply(res, ex::run_json(p, c)); });
    });
  });
  svr.Get("/api/tail", [&](const httplib::Request& req, httplib::Response& res) {
    answer(res, [&] {
      const ex::Params p = params_of(req, {"r", "point", "transient", "tail", "session"});
      with_job(jobs, s, p, "tail", [&](const core::RunControl& c) { json_reply(res, ex::tail_json(p, c)); });
    });
  });
  svr.Get("/api/overlays", [&](const httplib::Request& req, httplib::Response& res) {
    answer(res, [&] { json_reply(res, ex::overlays_json(params_of(req, {"r_min", "r_max"}))); });
  });
  svr.Get("/api/progress", [&](const httplib::Request& req, httplib::Response& res) {
    answer(res, [&] {
      const ex::Params p = params_of(req, {"session"});
      json_reply(res, jobs.progress(p.count("session") ? p.at("session") : "").dump());
    });
  });
  svr.Post("/api/export", [&](const httplib::Request& req, httplib::Response& res) {
    answer(res, [&] {
      const ex::Params p = params_of(req, {"r_min", "r_max", "coord", "lo", "hi", "width", "height", "iterations",
                                           "tail", "grid", "overlay", "session"});
      json_reply(res, ex::export_view(ex::parse_view(p), s.export_dir));
    });
  });
}

// The embedded page; / is index.html.  No file of the file system is ever served.
void page_routes(httplib::Server& svr) {
  svr.Get(R"(/([a-z_]*\.?[a-z]*))", [](const httplib::Request& req, httplib::Response& res) {
    std::string name = req.matches[1];
    if (name.empty()) name = "index.html";
    const auto it = ex::assets().find(name);
    if (it == ex::assets().end()) {
      res.status = 404;
      res.set_content(ex::error_json("no page '" + name + "'"), "application/json");
      return;
    }
    res.set_content(reinterpret_cast<const char*>(it->second.data), it->second.size, it->second.mime);
  });
  svr.set_error_handler([](const httplib::Request& req, httplib::Response& res) {
    if (res.body.empty())
      res.set_content(ex::error_json(fmt::format("HTTP {} for {}", res.status, req.path)), "application/json");
  });
  // MPFR keeps its constants (pi, log 2) in caches local to the thread that computed them; the server's worker
  // threads compute window bounds and classifications in MPFR and then end with the server, so each request frees
  // its thread's caches instead of leaving them to a thread exit that never frees them.
  svr.set_post_routing_handler(
      [](const httplib::Request&, httplib::Response&) { mpfr_free_cache2(MPFR_FREE_LOCAL_CACHE); });
}

// Opens `url` with xdg-open when it is on the PATH; never fails (a machine without a desktop just has no browser).
void open_browser(const std::string& url) {
  const char* path = std::getenv("PATH");
  bool found = false;
  for (std::string_view rest = path ? path : ""; !found && !rest.empty();) {
    const std::size_t c = std::min(rest.find(':'), rest.size());
    found = access((std::string(rest.substr(0, c)) + "/xdg-open").c_str(), X_OK) == 0;
    rest.remove_prefix(std::min(c + 1, rest.size()));
  }
  if (!found) {
    std::cout << "btob explore: no xdg-open on the PATH; open " << url << " in a browser" << std::endl;
    return;
  }
  pid_t pid;
  std::string u = url;
  char arg0[] = "xdg-open";
  char* argv[] = {arg0, u.data(), nullptr};
  posix_spawn_file_actions_t quiet;  // xdg-open's own complaints (no display, no browser) are not ours to print
  posix_spawn_file_actions_init(&quiet);
  posix_spawn_file_actions_addopen(&quiet, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&quiet, 2, "/dev/null", O_WRONLY, 0);
  const int rc = posix_spawnp(&pid, "xdg-open", &quiet, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&quiet);
  if (rc != 0) {
    std::cout << "btob explore: xdg-open failed; open " << url << " in a browser" << std::endl;
    return;
  }
  std::cout << "btob explore: asked xdg-open to show " << url << std::endl;
  std::thread([pid] { waitpid(pid, nullptr, 0); }).detach();  // reap it
}

bool loopback(const std::string& host) { return host == "127.0.0.1" || host == "localhost" || host == "::1"; }

void serve(const Settings& s) {
  core::require_threads(s.threads);
  httplib::Server svr;
  // SO_REUSEADDR only: httplib's default adds SO_REUSEPORT, with which a second explorer would share a busy port
  // silently instead of saying that it is taken.
  svr.set_socket_options([](socket_t sock) {
    int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  Jobs jobs;
  api_routes(svr, jobs, s);
  page_routes(svr);
  const int port = s.port == 0 ? svr.bind_to_any_port(s.host) : (svr.bind_to_port(s.host, s.port) ? s.port : -1);
  if (port < 0)
    throw std::runtime_error(
        fmt::format("cannot listen on {}:{} (in use, or not an address of this machine)", s.host, s.port));
  const std::string url =
      fmt::format("http://{}:{}/", s.host.find(':') != std::string::npos ? "[" + s.host + "]" : s.host, port);
  if (!loopback(s.host))
    std::cout << fmt::format(
        "btob explore: WARNING: listening on {} exposes the explorer to every machine that can reach "
        "it: anyone can run views (up to the work budget each) and the commands it serves (as large as "
        "their own limits allow) and write scenes and PNGs into '{}'; there is no authentication\n",
        s.host, s.export_dir);
  std::cout << "btob explore: serving " << url << " (exports go to '" << s.export_dir << "'; Ctrl-C stops)"
            << std::endl;
  if (!s.no_browser) open_browser(url);
  std::thread watch([&] {  // SIGINT/SIGTERM set the process's token: stop serving, cancel what runs
    while (!cancel_token().cancelled()) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    jobs.cancel_all();
    svr.stop();
  });
  svr.listen_after_bind();
  cancel_token().cancel();  // ends the watcher when the server stopped by itself
  watch.join();
  std::cout << "btob explore: stopped" << std::endl;
}

Register reg([](CLI::App& app) {
  auto s = std::make_shared<Settings>();
  CLI::App* c =
      app.add_subcommand("explore",
                         "Serve the bifurcation diagram to a browser, recomputed at every zoom (a server that "
                         "runs until stopped: no --dry-run; each view's cost is that of a small "
                         "bifurcation request)");
  c->add_option("--port", s->port, "TCP port, 0..65535 (0: any free port)")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
  c->add_option("--host", s->host, "address to listen on (default 127.0.0.1; any other exposes the explorer)");
  c->add_flag("--no-browser", s->no_browser, "do not open a browser");
  c->add_option("--export", s->export_dir, "folder the page's exports are written to (nothing else is written)")
      ->capture_default_str();
  c->add_option("--threads", s->threads, "OpenMP threads of each computation: " + core::threads_expected());
  c->callback([s] { serve(*s); });
});

}  // namespace
}  // namespace btob::cli
