// SPDX-License-Identifier: GPL-3.0-or-later
// The MPI job of cli/mpi.hpp: one process of rank 0 unless built with MPI (BTOB_MPI) and started by a launcher.
#include "cli/mpi.hpp"

#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <thread>
#include <unistd.h>

#ifdef BTOB_MPI
#include <mpi.h>
#endif

namespace btob::cli::mpi {
namespace {
struct State {
  bool initialised = false, checked = false, solo = false;
  int rank = 0, size = 1;
  Stats stats;
  std::filesystem::path remove_on_abort;  // RemoveOnAbort's folder, empty for none
};
State& state() {
  static State s;
  return s;
}

// One line on stderr in one write(2): the lines of several ranks sharing mpirun's stderr never interleave
// ("btob: rank btob: rank 0: ...", which operator<<'s pieces gave).
void say(const std::string& line) {
  std::cerr.flush();
  const std::string text = line + "\n";
  for (std::size_t at = 0; at < text.size();) {
    const ssize_t n = ::write(2, text.data() + at, text.size() - at);
    if (n <= 0) break;
    at += static_cast<std::size_t>(n);
  }
}

[[noreturn]] void end(int code) {
  std::cout.flush();
  std::cerr.flush();
  std::_Exit(code);  // as main's failed(): no exit-time cleanup of the libraries (HDF5), files are closed or removed
}

#ifdef BTOB_MPI
// A launcher's environment: Open MPI's mpirun, MPICH/Hydra or Slurm's PMI, PMIx (srun --mpi=pmix).
bool launched() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "PMI_RANK"})
    if (std::getenv(v)) return true;
  return false;
}

// One message of any size: its length, then pieces of at most 1 GiB (MPI counts are int).
constexpr std::size_t kPiece = std::size_t{1} << 30;
void send(const std::vector<char>& b, double seconds) {
  const std::uint64_t n = b.size();
  MPI_Send(&n, 1, MPI_UINT64_T, 0, 1, MPI_COMM_WORLD);
  MPI_Send(&seconds, 1, MPI_DOUBLE, 0, 2, MPI_COMM_WORLD);
  for (std::size_t at = 0; at < b.size(); at += kPiece)
    MPI_Send(b.data() + at, static_cast<int>(std::min(kPiece, b.size() - at)), MPI_BYTE, 0, 3, MPI_COMM_WORLD);
}
std::vector<char> receive(int from, double& seconds) {
  std::uint64_t n = 0;
  MPI_Recv(&n, 1, MPI_UINT64_T, from, 1, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  MPI_Recv(&seconds, 1, MPI_DOUBLE, from, 2, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  std::vector<char> b(static_cast<std::size_t>(n));
  for (std::size_t at = 0; at < b.size(); at += kPiece)
    MPI_Recv(b.data() + at, static_cast<int>(std::min(kPiece, b.size() - at)), MPI_BYTE, from, 3, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
  return b;
}
#endif
}  // namespace

bool available() {
#ifdef BTOB_MPI
  return true;
#else
  return false;
#endif
}

void init(int& argc, char**& argv) {
#ifdef BTOB_MPI
  if (!launched()) return;
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  State& s = state();
  s.initialised = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &s.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &s.size);
  s.stats.ranks = s.size;
#else
  (void)argc, (void)argv;
#endif
}

void finalize() {
#ifdef BTOB_MPI
  if (state().initialised) MPI_Finalize();
  state().initialised = false;
#endif
}

int rank() { return state().rank; }
int size() { return state().size; }
bool checked() { return state().checked; }
Stats& stats() { return state().stats; }

void checkpoint() {
  State& s = state();
  if (s.checked) return;
  s.checked = true;
#ifdef BTOB_MPI
  if (s.size == 1) return;
  int code = 0;  // this rank is fine; a failing rank sends its exit code in fail()
  int worst = 0;
  MPI_Allreduce(&code, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  int ok = 1, ranks_ok = 0;
  MPI_Allreduce(&ok, &ranks_ok, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  int none = s.size, first_bad = s.size;
  MPI_Allreduce(&none, &first_bad, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (worst != 0) {  // another rank failed before starting: it said why; end quietly with its status
    finalize();
    end(worst);
  }
#endif
}

void fail(const std::string& cause, int code, const std::string& label) {
  State& s = state();
  if (s.size == 1 || s.solo) {
    say("btob: " + label + cause);
    end(code);
  }
#ifdef BTOB_MPI
  if (!s.checked) {
    // Before any work: the other ranks are at the checkpoint or failing too; the same three reductions.
    s.checked = true;
    int worst = 0, ranks_ok = 0, first_bad = s.size, zero = 0;
    MPI_Allreduce(&code, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    MPI_Allreduce(&zero, &ranks_ok, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
    MPI_Allreduce(&s.rank, &first_bad, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    if (s.rank == first_bad) {
      if (ranks_ok == 0) say("btob: " + label + cause);  // every rank: a bad input, said once
      else say("btob: rank " + std::to_string(s.rank) + ": " + cause);
    }
    finalize();
    end(worst);
  }
  // 130/143: SIGINT/SIGTERM stopped this rank.  mpirun sends SIGTERM to every rank when one of them aborted or when
  // the user interrupted mpirun: the job is ending and its cause said already; end quietly (nothing was written).
  if (code == 130 || code == 143) end(code);
  say("btob: rank " + std::to_string(s.rank) + ": " + cause);
  std::cout.flush();
  std::cerr.flush();
  if (!s.remove_on_abort.empty()) {
    std::error_code ec;
    std::filesystem::remove_all(s.remove_on_abort, ec);  // best effort: the job is failing already
  }
  MPI_Abort(MPI_COMM_WORLD, code);
#endif
  end(code);
}

RemoveOnAbort::RemoveOnAbort(const std::string& staged_file) : unwinding_(std::uncaught_exceptions()) {
  const std::filesystem::path folder = std::filesystem::path(staged_file).parent_path();
  if (folder.filename().string().rfind(".btob-tmp-", 0) == 0) state().remove_on_abort = folder;
}
RemoveOnAbort::~RemoveOnAbort() {
  if (std::uncaught_exceptions() == unwinding_) state().remove_on_abort.clear();
}

void fail_everywhere(const std::string& cause, int code, const std::string& label) {
  if (state().rank == 0) say("btob: " + label + cause);
  finalize();
  end(code);
}

std::vector<char> broadcast(std::vector<char> bytes) {
#ifdef BTOB_MPI
  if (state().size == 1) return bytes;
  std::uint64_t n = bytes.size();
  MPI_Bcast(&n, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
  bytes.resize(static_cast<std::size_t>(n));
  for (std::size_t at = 0; at < bytes.size(); at += kPiece)
    MPI_Bcast(bytes.data() + at, static_cast<int>(std::min(kPiece, bytes.size() - at)), MPI_BYTE, 0, MPI_COMM_WORLD);
#endif
  return bytes;
}

std::vector<std::vector<char>> all_gather(std::vector<char> mine) {
  State& s = state();
  std::vector<std::vector<char>> all;
  if (s.size == 1) {
    all.push_back(std::move(mine));
    return all;
  }
#ifdef BTOB_MPI
  if (mine.size() > static_cast<std::size_t>(INT_MAX))
    throw std::length_error("all_gather: more than 2 GiB from a rank");
  const int n = static_cast<int>(mine.size());
  std::vector<int> sizes(static_cast<std::size_t>(s.size)), at(static_cast<std::size_t>(s.size), 0);
  MPI_Allgather(&n, 1, MPI_INT, sizes.data(), 1, MPI_INT, MPI_COMM_WORLD);
  long total = 0;
  for (std::size_t k = 0; k < sizes.size(); ++k) {
    if (total > INT_MAX) throw std::length_error("all_gather: more than 2 GiB in all");
    at[k] = static_cast<int>(total);
    total += sizes[k];
  }
  std::vector<char> got(static_cast<std::size_t>(total) + 1);  // + 1: a valid buffer when every rank sends none
  static char none = 0;
  MPI_Allgatherv(n ? mine.data() : &none, n, MPI_CHAR, got.data(), sizes.data(), at.data(), MPI_CHAR, MPI_COMM_WORLD);
  for (std::size_t k = 0; k < sizes.size(); ++k) all.emplace_back(got.begin() + at[k], got.begin() + at[k] + sizes[k]);
#endif
  return all;
}

std::vector<std::vector<char>> gather(std::vector<char> mine, double compute_seconds) {
  State& s = state();
  std::vector<std::vector<char>> all;
  Stats& st = s.stats;
  st.compute_min = st.compute_max = compute_seconds;
  st.bytes_total = st.bytes_max = 0;
  if (s.size == 1) {
    all.push_back(std::move(mine));
    return all;
  }
#ifdef BTOB_MPI
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  // The slowest rank's work ends here: what follows is the transfer alone.  Polled with a 1 ms sleep rather than
  // MPI_Barrier, which spins: a rank that finished early leaves its core to the others (oversubscribed or shared
  // nodes) instead of burning it.
  MPI_Request barrier;
  MPI_Ibarrier(MPI_COMM_WORLD, &barrier);
  for (int done = 0; MPI_Test(&barrier, &done, MPI_STATUS_IGNORE), !done;)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  const auto t1 = clock::now();
  if (s.rank != 0) {
    send(mine, compute_seconds);
    return all;
  }
  all.resize(static_cast<std::size_t>(s.size));
  all[0] = std::move(mine);
  for (int k = 1; k < s.size; ++k) {
    double sec = 0;
    all[static_cast<std::size_t>(k)] = receive(k, sec);
    const std::uint64_t b = all[static_cast<std::size_t>(k)].size();
    st.bytes_total += b;
    st.bytes_max = std::max(st.bytes_max, b);
    st.compute_min = std::min(st.compute_min, sec);
    st.compute_max = std::max(st.compute_max, sec);
  }
  st.wait_seconds = std::chrono::duration<double>(t1 - t0).count();
  st.gather_seconds = std::chrono::duration<double>(clock::now() - t1).count();
#endif
  return all;
}

std::vector<const CLI::App*>& request_apps() {
  static std::vector<const CLI::App*> v;
  return v;
}

namespace {
bool is_request(const CLI::App* a) {
  const auto& req = request_apps();
  return std::find(req.begin(), req.end(), a) != req.end();
}
bool has_request_below(CLI::App* a) {
  for (CLI::App* sub : a->get_subcommands([](CLI::App*) { return true; }))
    if (is_request(sub) || has_request_below(sub)) return true;
  return false;
}
}  // namespace

void guard_root_only(CLI::App& app) {
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
    if (is_request(sub) || sub->get_name() == "run") continue;
    guard_root_only(*sub);
    if (has_request_below(sub)) continue;  // a group such as `windows`: its request-based commands split
    sub->preparse_callback([](std::size_t) {
      if (state().size == 1) return;
      if (state().rank != 0) throw RootOnly{};
      state().solo = true;  // rank 0 works alone: its errors are a single process's
    });
  }
}

}  // namespace btob::cli::mpi
