// SPDX-License-Identifier: GPL-3.0-or-later
// The checkpoint file of a resumable sweep (io/checkpoint.hpp): its header, its records, their validation.
#include "io/checkpoint.hpp"
#include "core/run.hpp"
#include "io/result_files.hpp"

#include <btob/build_info.hpp>

#include <omp.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <sys/file.h>
#include <unistd.h>

namespace btob::io {
namespace {
constexpr const char* kMagic = "btob-checkpoint 1\n";

// FNV-1a, 64 bits: tells a whole record from one cut short or overwritten (not a defence against tampering).  Its
// offset basis is the published 14695981039346656037 without the last digit, as the format has had it from the start
// (any basis serves; kept so that the format stays the same, tests/test_checkpoint.cpp recomputes it).
std::uint64_t fnv1a(const char* p, std::size_t n) {
  std::uint64_t h = 1469598103934665603ull;
  for (std::size_t i = 0; i < n; ++i) h = (h ^ static_cast<unsigned char>(p[i])) * 1099511628211ull;
  return h;
}

std::string record(const std::vector<char>& payload) {
  std::string r(16, '\0');
  const std::uint64_t size = payload.size(), hash = fnv1a(payload.data(), payload.size());
  std::memcpy(r.data(), &size, 8);
  std::memcpy(r.data() + 8, &hash, 8);
  return r.append(payload.begin(), payload.end());
}

// Writes `text` at the end of `path` (or into a new file) and flushes it to the disk before returning.
void write_synced(const fs::path& path, const std::string& text, bool append) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | (append ? O_APPEND : O_TRUNC), 0644);
  bool ok = fd >= 0;
  for (std::size_t at = 0; ok && at < text.size();) {
    const ssize_t k = ::write(fd, text.data() + at, text.size() - at);
    ok = k > 0;
    at += ok ? static_cast<std::size_t>(k) : 0;
  }
  ok = ok && ::fsync(fd) == 0;
  const int err = errno;
  if (fd >= 0) ::close(fd);
  if (!ok) throw_file_error("cannot write the checkpoint", path, std::error_code(err, std::generic_category()));
}

// The first "key: value" line of `want` that `got` lacks or holds with another value, as "key: A there, B here".
std::string first_difference(const std::string& got, const std::string& want) {
  const auto lines = [](const std::string& s) {
    std::map<std::string, std::string> m;
    std::istringstream in(s);
    for (std::string l; std::getline(in, l);) {
      const auto c = l.find(": ");
      m[l.substr(0, c)] = c == std::string::npos ? "" : l.substr(c + 2);
    }
    return m;
  };
  const auto g = lines(got), w = lines(want);
  std::istringstream in(want);
  for (std::string l; std::getline(in, l);) {
    const std::string key = l.substr(0, l.find(": "));
    const auto it = g.find(key);
    if (it == g.end()) return fmt::format("{}: absent there, '{}' here", key, w.at(key));
    if (it->second != w.at(key)) return fmt::format("{}: '{}' there, '{}' here", key, it->second, w.at(key));
  }
  for (const auto& [key, value] : g)
    if (!w.count(key)) return fmt::format("{}: '{}' there, absent here", key, value);
  return "the same fields in another order";
}

// Reads the records of an existing checkpoint file into `cp` (truncating a record cut short), or says why it is
// refused.
std::string read_existing(Checkpoint& cp, const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string magic = kMagic;
  const auto refuse = [&](const std::string& why) {
    return fmt::format("{}: {}; remove it to start again, or resume with the request that made it", path.string(), why);
  };
  if (!in.good() && !in.eof()) return refuse("cannot be read");
  if (bytes.compare(0, magic.size(), magic) != 0) return refuse("not a btob checkpoint");
  std::size_t at = magic.size();
  std::size_t records = 0;
  while (bytes.size() - at >= 16) {
    std::uint64_t size = 0, hash = 0;
    std::memcpy(&size, bytes.data() + at, 8);
    std::memcpy(&hash, bytes.data() + at + 8, 8);
    if (size > bytes.size() - at - 16 || fnv1a(bytes.data() + at + 16, size) != hash) break;
    const char* payload = bytes.data() + at + 16;
    if (records++ == 0) {
      if (std::string(payload, size) != cp.identity)
        return refuse("a checkpoint of another request or build (" +
                      first_difference(std::string(payload, size), cp.identity) + ")");
    } else {
      auto rec = core::unpack<std::pair<std::vector<std::size_t>, std::vector<char>>>(
          std::vector<char>(payload, payload + size));
      cp.done.insert(cp.done.end(), rec.first.begin(), rec.first.end());
      cp.parts.push_back(std::move(rec.second));
    }
    at += 16 + size;
  }
  if (records == 0) return refuse("its header is cut short");
  if (at < bytes.size()) fs::resize_file(path, at);  // a record cut short by a kill: dropped
  return "";
}

// Opens and locks a file (never replaced once made: appended to, truncated, so the lock stays on it).
std::string lock(Checkpoint& cp, const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDWR);
  if (fd < 0) return fmt::format("{}: cannot be opened ({})", path.string(), std::strerror(errno));
  cp.locks.push_back(fd);
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0)
    return fmt::format("{}: in use by another run of btob (wait for it to end, or end it)", path.string());
  return "";
}

// Starts the file with its header (written to a temporary file, renamed into place) when it is absent.
bool start(const Checkpoint& cp, const fs::path& path) {
  if (fs::exists(path)) return false;
  fs::create_directories(path.parent_path().empty() ? "." : path.parent_path());
  const fs::path tmp = path.string() + ".tmp";
  write_synced(tmp, kMagic + record(std::vector<char>(cp.identity.begin(), cp.identity.end())), false);
  fs::rename(tmp, path);
  return true;
}

// The files rank `rank` of `ranks` opens: its own first, then the earlier ones that fall to it.
std::vector<fs::path> files_of(const fs::path& path, std::size_t rank, std::size_t ranks,
                               const std::vector<std::size_t>& earlier) {
  std::vector<fs::path> f{checkpoint_file(path, rank)};
  for (const std::size_t k : earlier)
    if (k % ranks == rank && k != rank) f.push_back(checkpoint_file(path, k));
  return f;
}

}  // namespace

fs::path checkpoint_file(const fs::path& path, std::size_t k) {
  return k == 0 ? path : fs::path(path.string() + "." + std::to_string(k));
}

std::vector<std::size_t> checkpoint_rank_files(const fs::path& path) {
  std::vector<std::size_t> ks;
  const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  const std::string stem = path.filename().string() + ".";
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() <= stem.size() || name.compare(0, stem.size(), stem) != 0) continue;
    const std::string digits = name.substr(stem.size());
    if (digits.size() > 9 || digits[0] == '0' ||
        !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
      continue;  // NAME.checkpoint.tmp, or not a rank's number as checkpoint_file writes it
    ks.push_back(std::stoul(digits));
  }
  std::sort(ks.begin(), ks.end());
  return ks;
}

std::string open_checkpoint_files(Checkpoint& cp, std::size_t rank, std::size_t ranks,
                                  const std::vector<std::size_t>& earlier) {
  try {
    cp.own = checkpoint_file(cp.path, rank);
    cp.job.clear();
    for (std::size_t k = 0; k < ranks; ++k) cp.job.push_back(checkpoint_file(cp.path, k));
    for (const std::size_t k : earlier)
      if (k >= ranks) cp.job.push_back(checkpoint_file(cp.path, k));
    for (const fs::path& f : files_of(cp.path, rank, ranks, earlier)) {
      if (f == cp.own) cp.created = start(cp, f);
      std::string error = lock(cp, f);
      if (error.empty()) error = read_existing(cp, f);
      if (!error.empty()) return error;
    }
    return check_done(cp.path, cp.done);
  } catch (const std::exception& e) {
    return e.what();
  }
}

std::string open_checkpoint_file(Checkpoint& cp) {
  const std::string error = open_checkpoint_files(cp, 0, 1, checkpoint_rank_files(cp.path));
  if (!error.empty()) discard_created(cp);
  return error;
}

std::string check_done(const fs::path& path, std::vector<std::size_t>& done) {
  std::sort(done.begin(), done.end());
  const auto twice = std::adjacent_find(done.begin(), done.end());
  if (twice == done.end()) return "";
  return fmt::format("{}: item {} is held by two of its files (files of two runs mixed); remove them to start again",
                     path.string(), *twice);
}

void discard_created(const Checkpoint& cp) {
  std::error_code ec;
  if (cp.created) fs::remove(cp.own, ec);
}

std::string checkpoint_identity(const std::string& command, const core::Args& args) {
  std::string s = fmt::format("btob: {}\ncommit: {}\ndirty: {}\ncommand: {}\n", build::version, build::git_commit,
                              build::git_dirty, command);
  for (const auto& [key, values] : args) {
    s += key + ":";
    for (const auto& v : values) s += " " + v;
    s += "\n";
  }
  return s;
}

void append_checkpoint(const Checkpoint& cp, const std::vector<std::size_t>& items, const std::vector<char>& part) {
  write_synced(cp.own, record(core::pack(std::make_pair(items, part))), true);
}

void remove_checkpoint(const Checkpoint& cp) {
  std::error_code ec;
  for (const fs::path& f : cp.job) fs::remove(f, ec);
}

Checkpoint::~Checkpoint() {
  for (const int fd : locks) ::close(fd);  // releases the flocks
}

std::size_t checkpoint_chunk(std::size_t share, int threads) {
  const std::size_t t = static_cast<std::size_t>(core::thread_count(threads));
  return std::max<std::size_t>({1, (share + checkpoint_rounds - 1) / checkpoint_rounds, t});
}

namespace detail {
std::vector<std::size_t> items_left(std::size_t n, const std::vector<std::size_t>& done) {
  std::vector<std::size_t> left;
  for (std::size_t i = 0, d = 0; i < n; ++i) {
    while (d < done.size() && done[d] < i) ++d;
    if (d < done.size() && done[d] == i) continue;
    left.push_back(i);
  }
  return left;
}
}  // namespace detail

}  // namespace btob::io
