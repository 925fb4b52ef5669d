// SPDX-License-Identifier: GPL-3.0-or-later
// The checkpoint of a resumable sweep (io/checkpoint.hpp) without MPI: the ranks of a job simulated as checkpoints
// opened side by side on one folder.  Each rank appends only its own parts to its own file; a job resumed with
// another number of ranks reads every earlier file once (file K on rank K mod P), so the union of the ranks'
// finished items is every item once; a single process reads an MPI job's files; the one-process file is the
// documented format byte for byte; a file of another request, a file in use and an item held twice are refused,
// leaving the folder as it was.  core::take_rows over a rank's interleaved parts gives its rows in item order.
#include "core/pack.hpp"
#include "core/sweep.hpp"
#include "io/checkpoint.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

namespace toy {
// A sweep of n items whose part names its rows (core::HasRows): row i is (i, sqrt(i), i^2 / 7), a count per item.
struct Req {
  std::size_t n = 0;
  std::size_t work_items() const { return n; }
};
struct Part {
  std::vector<std::size_t> items;
  std::vector<double> row;           // 3 per item
  std::vector<std::uint32_t> count;  // 1 per item
  template <class A> void members(A& a) { a(items, row, count); }
  template <class A> void rows(A& a) { a("row", row); }
};
inline int calls_left = -1;  // run_part calls before it throws (a kill), -1: no limit
Part run_part(const Req&, const std::vector<std::size_t>& items, const btob::core::RunControl&) {
  if (calls_left == 0) throw std::runtime_error("killed");
  if (calls_left > 0) --calls_left;
  Part p;
  p.items = items;
  for (const std::size_t i : items) {
    const double x = static_cast<double>(i);
    p.row.insert(p.row.end(), {x, std::sqrt(x), x * x / 7});
    p.count.push_back(static_cast<std::uint32_t>(i % 5));
  }
  return p;
}
struct Result {
  std::vector<double> row;
  std::vector<std::uint32_t> count;
};
Result merge(const Req& r, std::vector<Part> parts) {
  const auto order = btob::core::item_order(parts, r.n);
  Result res;
  res.row = btob::core::merge_rows<Part, double>(
      parts, order, 3, [](const Part& p) -> const auto& { return p.row; });
  res.count = btob::core::merge_rows<Part, std::uint32_t>(
      parts, order, 1, [](const Part& p) -> const auto& { return p.count; });
  return res;
}
}  // namespace toy

namespace {
using namespace btob;
namespace fs = std::filesystem;

// A fresh folder per test, removed after it.
struct Folder {
  fs::path dir;
  explicit Folder(const std::string& name)
      : dir(fs::temp_directory_path() / ("btob_checkpoint_" + name + "_" + std::to_string(getpid()))) {
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~Folder() { fs::remove_all(dir); }
};

const std::string kIdentity = "btob: test\ncommand: toy\nn: 60\n";

// Opens rank `rank` of `ranks` on `base` with the earlier rank files found there.
std::string open(io::Checkpoint& cp, const fs::path& base, std::size_t rank, std::size_t ranks,
                 const std::string& identity = kIdentity) {
  cp.path = base;
  cp.identity = identity;
  return io::open_checkpoint_files(cp, rank, ranks, io::checkpoint_rank_files(base));
}

std::vector<std::size_t> items_of(const std::vector<toy::Part>& parts) {
  std::vector<std::size_t> v;
  for (const auto& p : parts) v.insert(v.end(), p.items.begin(), p.items.end());
  std::sort(v.begin(), v.end());
  return v;
}

TEST(Checkpoint, RanksKeepTheirOwnPartsAndAJobResumesWithAnotherCount) {
  Folder f("ranks");
  const fs::path base = f.dir / "x.checkpoint";
  const toy::Req req{60};
  core::RunControl c;
  c.threads = 1;
  // A job of 3 ranks killed after 2 rounds of each rank (rounds of 1 item: chunk = ceil(20 / 32) = 1).
  for (std::size_t k = 0; k < 3; ++k) {
    io::Checkpoint cp;
    ASSERT_EQ(open(cp, base, k, 3), "");
    toy::calls_left = 2;
    EXPECT_THROW(io::run_in_rounds(req, c, cp, io::Ranks{3, k, {}, {}}), std::runtime_error);
  }
  toy::calls_left = -1;
  EXPECT_EQ(io::checkpoint_rank_files(base), (std::vector<std::size_t>{1, 2}));
  {
    // Resumed by 2 ranks, both alive together (their locks on different files): rank 0 reads files 0 and 2.
    io::Checkpoint a, b;
    ASSERT_EQ(open(a, base, 0, 2), "");
    ASSERT_EQ(open(b, base, 1, 2), "");
    EXPECT_EQ(a.done, (std::vector<std::size_t>{0, 2, 3, 5}));
    EXPECT_EQ(b.done, (std::vector<std::size_t>{1, 4}));
    EXPECT_EQ(a.job, (std::vector<fs::path>{base, io::checkpoint_file(base, 1), io::checkpoint_file(base, 2)}));
    io::Checkpoint third;  // another run on the same files while this one lives
    EXPECT_NE(open(third, base, 0, 1).find("in use by another run"), std::string::npos);
    std::vector<std::size_t> all = a.done;
    all.insert(all.end(), b.done.begin(), b.done.end());
    ASSERT_EQ(io::check_done(base, all), "");
    a.done = b.done = all;  // what cli::open_checkpoint's allgather gives every rank
    toy::calls_left = 3;    // killed again after 3 more rounds each
    EXPECT_THROW(io::run_in_rounds(req, c, a, io::Ranks{2, 0, {}, {}}), std::runtime_error);
    toy::calls_left = 3;
    EXPECT_THROW(io::run_in_rounds(req, c, b, io::Ranks{2, 1, {}, {}}), std::runtime_error);
  }
  toy::calls_left = -1;
  // A single process reads every file: each item once (none recomputed), then computes the rest.
  io::Checkpoint one;
  ASSERT_EQ(open(one, base, 0, 1), "");
  EXPECT_EQ(one.done.size(), 6u + 6u);
  auto mine = io::run_in_rounds(req, c, one, io::alone());
  EXPECT_EQ(items_of(mine.parts), core::all_items(60));
  const toy::Result whole = toy::merge(req, {toy::run_part(req, core::all_items(60), c)});
  const toy::Result resumed = toy::merge(req, std::move(mine.parts));
  EXPECT_EQ(0, std::memcmp(whole.row.data(), resumed.row.data(), whole.row.size() * sizeof(double)));
  EXPECT_EQ(whole.count, resumed.count);
  io::remove_checkpoint(one);
  EXPECT_FALSE(fs::exists(base) || fs::exists(io::checkpoint_file(base, 1)) ||
               fs::exists(io::checkpoint_file(base, 2)));
}

// The record hash of the format, computed here from its definition (not btob's code): FNV-1a's prime and step, from
// the offset basis the format has always used, 1469598103934665603 (FNV's published basis 14695981039346656037
// without its last digit; any basis tells a whole record from a cut one, and keeping it keeps the files readable).
std::uint64_t fnv(const std::string& s) {
  std::uint64_t h = 1469598103934665603ull;
  for (const unsigned char ch : s) h = (h ^ ch) * 0x100000001b3ull;
  return h;
}
std::string record(const std::string& payload) {
  std::string r(16, '\0');
  const std::uint64_t size = payload.size(), hash = fnv(payload);
  std::memcpy(r.data(), &size, 8);
  std::memcpy(r.data() + 8, &hash, 8);
  return r + payload;
}

TEST(Checkpoint, OneProcessWritesTheDocumentedFormatInOneFile) {
  Folder f("format");
  const fs::path base = f.dir / "x.checkpoint";
  {
    io::Checkpoint cp;
    cp.path = base;
    cp.identity = kIdentity;
    ASSERT_EQ(io::open_checkpoint_file(cp), "");
    io::append_checkpoint(cp, {1, 4}, {'a', 'b', 'c'});
  }
  // [uint64 2][1][4] then the packed vector<char> [uint64 3]abc
  std::string part;
  for (const std::uint64_t v : {2ull, 1ull, 4ull, 3ull}) part.append(reinterpret_cast<const char*>(&v), 8);
  part += "abc";
  std::ifstream in(base, std::ios::binary);
  const std::string got((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(got, "btob-checkpoint 1\n" + record(kIdentity) + record(part));
  EXPECT_EQ(std::distance(fs::directory_iterator(f.dir), fs::directory_iterator()), 1);  // no other file
}

TEST(Checkpoint, ARefusedRunLeavesTheFolderAsItWas) {
  Folder f("refused");
  const fs::path base = f.dir / "x.checkpoint";
  {
    io::Checkpoint other;  // rank 2 of a job of another request
    ASSERT_EQ(open(other, base, 2, 3, "btob: test\ncommand: toy\nn: 61\n"), "");
  }
  io::Checkpoint cp;
  cp.path = base;
  cp.identity = kIdentity;
  const std::string why = io::open_checkpoint_file(cp);
  EXPECT_NE(why.find("x.checkpoint.2: a checkpoint of another request or build (n: '61' there, '60' here)"),
            std::string::npos)
      << why;
  EXPECT_FALSE(fs::exists(base)) << "the refused run left the file it started";
  EXPECT_TRUE(fs::exists(io::checkpoint_file(base, 2)));
}

TEST(Checkpoint, AnItemInTwoFilesIsRefused) {
  Folder f("twice");
  const fs::path base = f.dir / "x.checkpoint";
  for (std::size_t k = 0; k < 2; ++k) {
    io::Checkpoint cp;
    ASSERT_EQ(open(cp, base, k, 2), "");
    io::append_checkpoint(cp, {3}, core::pack(toy::Part{}));
  }
  io::Checkpoint cp;
  EXPECT_NE(open(cp, base, 0, 1).find("item 3 is held by two of its files"), std::string::npos);
}

TEST(Checkpoint, TakeRowsOfInterleavedPartsIsInItemOrder) {
  const toy::Req req{12};
  const core::RunControl c;
  // A rank's parts as a resumed run holds them: an earlier run's, then its own rounds', items interleaved.
  std::vector<toy::Part> parts{toy::run_part(req, {1, 5, 9}, c), toy::run_part(req, {0, 6}, c),
                               toy::run_part(req, {2, 3, 11}, c)};
  const core::RowSet rows = core::take_rows(parts, 12);
  toy::Part direct = toy::run_part(req, {0, 1, 2, 3, 5, 6, 9, 11}, c);
  EXPECT_EQ(rows.items, direct.items);
  ASSERT_EQ(rows.columns.size(), 1u);
  EXPECT_EQ(rows.columns[0].name, "row");
  EXPECT_EQ(std::get<std::vector<double>>(rows.columns[0].data), direct.row);
  for (const auto& p : parts) EXPECT_TRUE(p.row.empty()) << "the rows were moved out of the parts";
  EXPECT_EQ(parts[2].count, (std::vector<std::uint32_t>{2, 3, 1}));  // the thin rest stays
  // A rank without parts names the same columns, empty.
  std::vector<toy::Part> none;
  const core::RowSet empty = core::take_rows(none, 12);
  ASSERT_EQ(empty.columns.size(), 1u);
  EXPECT_TRUE(empty.items.empty());
  EXPECT_EQ(empty.columns[0].size(), 0u);
}

}  // namespace
