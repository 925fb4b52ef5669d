// SPDX-License-Identifier: GPL-3.0-or-later
// ResultFiles: stage every file of a result in a temporary folder, move them into place together.
#include "io/result_files.hpp"
#include "core/request.hpp"
#include "io/cancel.hpp"
#include "io/latex.hpp"

#include <H5Cpp.h>
#include <fmt/format.h>
#include <hdf5_hl.h>
#include <nlohmann/json.hpp>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <iostream>
#include <iterator>
#include <limits>
#include <optional>
#include <string_view>

namespace btob::io {

[[noreturn]] void throw_file_error(const std::string& what, const fs::path& path, const std::error_code& ec) {
  throw std::runtime_error(fmt::format("{} '{}': {}", what, path.string(), ec ? ec.message() : std::strerror(errno)));
}

namespace {
// The nearest existing ancestor of `p` (the temporary folder lives there, on the same file system as the
// output, so that commit() is a rename).
fs::path existing_ancestor(fs::path p) {
  p = fs::absolute(p);
  std::error_code ec;
  while (!p.empty() && !fs::is_directory(p, ec)) {
    if (p == p.parent_path()) break;
    p = p.parent_path();
  }
  return p;
}
std::atomic<int> counter{0};

// This host's name as a field of a staging folder's name ('-' separates the fields, so it becomes '_').
std::string host_field() {
  char h[256] = {};
  if (gethostname(h, sizeof h - 1) != 0 || h[0] == '\0') return "host";
  std::string s(h);
  std::replace(s.begin(), s.end(), '-', '_');
  return s;
}

// The value of `s` when it is a decimal number alone (digits, no sign or space) that fits a long.
std::optional<long> decimal(std::string_view s) {
  long v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || s.front() == '-' || ec != std::errc{} || end != s.data() + s.size()) return std::nullopt;
  return v;
}

// Whether the staging folder `folder` (.btob-tmp-NAME-HOST-PID-N) of result `name` was left by a process of this host
// that no longer runs: killed outright (SIGKILL, the out-of-memory killer, a batch system's hard limit) before its
// ResultFiles could remove it.  A folder of another host (its PID means nothing here), of a live process, or of a
// process this one may not signal (EPERM: it exists) is not; nor is a name that does not parse.
bool stale_staging(const std::string& folder, const std::string& name, const std::string& host) {
  const std::string prefix = ".btob-tmp-" + name + "-" + host + "-";
  if (folder.rfind(prefix, 0) != 0) return false;
  const std::string_view rest = std::string_view(folder).substr(prefix.size());  // PID-N
  const auto dash = rest.find('-');
  if (dash == std::string_view::npos) return false;
  const std::optional<long> pid = decimal(rest.substr(0, dash)), n = decimal(rest.substr(dash + 1));
  if (!pid || !n || *pid <= 0 || *pid > std::numeric_limits<pid_t>::max() || *pid == static_cast<long>(getpid()))
    return false;
  return kill(static_cast<pid_t>(*pid), 0) != 0 && errno == ESRCH;
}

// Removes from `base` the stale staging folders of result `name` (stale_staging): a run killed outright leaves its
// staged files behind (no handler runs on SIGKILL), and the next run of the same result into the same place cleans
// them.  Best effort: a folder that cannot be listed or removed is left.
void remove_stale_staging(const fs::path& base, const std::string& name, const std::string& host) {
  std::error_code ec;
  for (fs::directory_iterator it(base, ec), end; !ec && it != end; it.increment(ec))
    if (stale_staging(it->path().filename().string(), name, host)) {
      std::error_code rm;
      fs::remove_all(it->path(), rm);
    }
}
}  // namespace

ResultFiles::ResultFiles(fs::path out, std::string name) : out_(std::move(out)), name_(std::move(name)) {
  if (name_.empty() || name_.find('/') != std::string::npos)
    throw core::InvalidField("name", fmt::format("'{}'", name_), "a file stem without '/'");
  std::error_code ec;
  if (fs::exists(out_, ec) && !fs::is_directory(out_, ec))
    throw core::InvalidField("out", fmt::format("'{}'", out_.string()), "a folder (it is a file)");
  const fs::path base = existing_ancestor(out_);
  const std::string host = host_field();
  remove_stale_staging(base, name_, host);
  tmp_ = base / fmt::format(".btob-tmp-{}-{}-{}-{}", name_, host, getpid(), counter.fetch_add(1));
  if (!fs::create_directory(tmp_, ec) || ec) throw_file_error("out: cannot write in", base, ec);
}

ResultFiles::~ResultFiles() {
  if (!committed_) {
    std::error_code ec;
    fs::remove_all(tmp_, ec);
  }
}

fs::path ResultFiles::staged(const std::string& filename) {
  if (std::find(files_.begin(), files_.end(), filename) == files_.end()) files_.push_back(filename);
  return tmp_ / filename;
}

void ResultFiles::text(const std::string& filename, const std::string& content) {
  const fs::path p = staged(filename);
  std::ofstream f(p, std::ios::binary);
  if (f) f << content;
  if (f) f.close();
  if (!f) throw_file_error("cannot write", final_path(filename), {});
}

void ResultFiles::tables(const core::Tables& t) {
  for (const auto& [role, content] : t) text(core::table_file(name_, role), content);
  for (const auto& table : t) table_roles_.push_back(table.first);
}

void ResultFiles::latex(const std::string& command_line, const std::string& caption) {
  for (const std::string& role : table_roles_) {
    const std::string csv = core::table_file(name_, role);
    std::string file = csv;
    file.replace(file.size() - 4, 4, ".tex");
    // The staged CSV as it is now: under MPI the ranks append a table's lines after the header given to tables().
    std::ifstream in(staged(csv), std::ios::binary);
    const std::string written((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in && !in.eof()) throw std::runtime_error("cannot read back the staged table " + staged(csv).string());
    text(file, latex_document(written, status_, command_line, caption + (role.empty() ? "" : " (" + role + ")")));
  }
}

namespace {
template <class V> const H5::PredType& h5_type() {
  if constexpr (std::is_same_v<V, double>) return H5::PredType::NATIVE_DOUBLE;
  else if constexpr (std::is_same_v<V, std::uint32_t>) return H5::PredType::NATIVE_UINT32;
  else if constexpr (std::is_same_v<V, std::uint64_t>) return H5::PredType::NATIVE_UINT64;
  else return H5::PredType::NATIVE_UINT8;
}
void string_attr(H5::H5Object& o, const std::string& k, const std::string& v) {
  // Variable-length UTF-8 strings: h5py reads them as str, not bytes.
  H5::StrType t(H5::PredType::C_S1, H5T_VARIABLE);
  t.setCset(H5T_CSET_UTF8);
  H5::DataSpace scalar(H5S_SCALAR);
  o.createAttribute(k, t, scalar).write(t, v);
}
// A 1-D dataset of variable-length UTF-8 strings (exact decimals, word names) with units, axes and description.
void string_dataset(H5::H5File& file, const core::DecimalView& d) {
  H5::StrType t(H5::PredType::C_S1, H5T_VARIABLE);
  t.setCset(H5T_CSET_UTF8);
  const hsize_t n = d.data->size();
  H5::DataSpace space(1, &n);
  H5::DataSet ds = file.createDataSet(d.name, t, space);
  std::vector<const char*> ptrs;
  for (const auto& s : *d.data) ptrs.push_back(s.c_str());
  if (n > 0) ds.write(ptrs.data(), t);
  string_attr(ds, "units", d.units);
  string_attr(ds, "axes", d.axes);
  string_attr(ds, "description", d.description);
}

// The axis labels of an array ("r, theta bin" -> {"r", "theta bin"}): split at the commas outside brackets, so a
// label may say what its axis holds ("point, (x, y, z)" -> {"point", "(x, y, z)"}).
std::size_t label_end(const std::string& axes, std::size_t start) {
  int depth = 0;
  for (std::size_t i = start; i < axes.size(); ++i) {
    const char ch = axes[i];
    if (ch == '(' || ch == '[') ++depth;
    else if ((ch == ')' || ch == ']') && depth > 0) --depth;
    else if (ch == ',' && depth == 0) return i;
  }
  return axes.size();
}
std::vector<std::string> axis_labels(const std::string& axes) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= axes.size()) {
    const std::size_t end = label_end(axes, start);
    std::string l = axes.substr(start, end - start);
    while (!l.empty() && l.front() == ' ') l.erase(l.begin());
    while (!l.empty() && l.back() == ' ') l.pop_back();
    out.push_back(l);
    start = end + 1;
  }
  return out;
}

// The length of the 1-D array or string dataset `name` of c (none: no such 1-D dataset).
std::optional<std::size_t> coordinate_length(const core::Contents& c, const std::string& name) {
  if (const core::ArrayView* s = c.find(name))
    return s->dims.size() == 1 ? std::optional<std::size_t>(s->dims[0]) : std::nullopt;
  for (const auto& t : c.texts)
    if (t.name == name) return t.data->size();
  return std::nullopt;
}

// Dimension scales: each axis of each dataset whose coordinates are an array or a string dataset of the result (the
// axis label itself, or Contents::coordinates[label]) gets it attached as its H5DS scale, named by the label.
void attach_scales(H5::H5File& file, const core::Contents& c) {
  std::map<std::string, bool> is_scale;
  for (const auto& a : c.arrays) {
    const std::vector<std::string> labels = axis_labels(a.axes);
    if (labels.size() != a.dims.size()) continue;
    for (std::size_t i = 0; i < labels.size(); ++i) {
      const auto it = c.coordinates.find(labels[i]);
      const std::string coord = it != c.coordinates.end() ? it->second : labels[i];
      if (coord == a.name || coordinate_length(c, coord) != a.dims[i]) continue;
      H5::DataSet scale = file.openDataSet(coord), ds = file.openDataSet(a.name);
      if (!is_scale[coord] && H5DSset_scale(scale.getId(), labels[i].c_str()) < 0)
        throw H5::DataSetIException("H5DSset_scale", coord);
      is_scale[coord] = true;
      if (H5DSattach_scale(ds.getId(), scale.getId(), static_cast<unsigned>(i)) < 0)
        throw H5::DataSetIException("H5DSattach_scale", a.name);
      if (H5DSset_label(ds.getId(), static_cast<unsigned>(i), labels[i].c_str()) < 0)
        throw H5::DataSetIException("H5DSset_label", a.name);
    }
  }
}

// The file's root attributes: strings, doubles and longs as scalars.
void write_root_attrs(H5::H5File& file, const Attrs& attrs) {
  H5::Group root = file.openGroup("/");
  for (const auto& [k, v] : attrs) {
    H5::DataSpace scalar(H5S_SCALAR);
    if (const auto* s = std::get_if<std::string>(&v)) string_attr(root, k, *s);
    else if (const auto* d = std::get_if<double>(&v))
      root.createAttribute(k, H5::PredType::NATIVE_DOUBLE, scalar).write(H5::PredType::NATIVE_DOUBLE, d);
    else {
      const long l = std::get<long>(v);
      root.createAttribute(k, H5::PredType::NATIVE_LONG, scalar).write(H5::PredType::NATIVE_LONG, &l);
    }
  }
}

// What kind of number each dataset or root attribute of c.status holds (core::Status): attributes status, basis
// and (estimates) confidence on the dataset; on the root group as NAME.status, NAME.basis, NAME.confidence when
// NAME is a root attribute (a verdict's or an orbit's numbers are attributes).
void write_status(H5::H5File& file, const core::Contents& c) {
  H5::Group root = file.openGroup("/");
  for (const auto& [name, st] : c.status) {
    const auto put = [&](H5::H5Object& o, const std::string& prefix) {
      string_attr(o, prefix + "status", st.kind);
      string_attr(o, prefix + "basis", st.basis);
      if (!st.confidence.empty()) string_attr(o, prefix + "confidence", st.confidence);
    };
    if (file.nameExists(name)) {
      H5::DataSet ds = file.openDataSet(name);
      put(ds, "");
    } else if (c.attrs.count(name)) {
      put(root, name + ".");
    } else {
      throw std::logic_error("result status of '" + name + "': no dataset or attribute of that name");
    }
  }
}

// The chunk of an array of `total` elements with dimensions d: at most about 2^18 elements, halving each dimension
// in turn; empty (a contiguous dataset) below 4096 elements.
std::vector<hsize_t> array_chunk(const std::vector<hsize_t>& d, std::size_t total) {
  if (total < 4096) return {};
  std::vector<hsize_t> chunk = d;
  std::size_t n = total;
  for (auto& x : chunk)
    while (n > (1u << 18) && x > 1) {
      n /= 2;
      x = (x + 1) / 2;
    }
  return chunk;
}

// The creation properties of an array with that chunk: chunked and deflated from 4096 elements on (density images
// are mostly empty).
H5::DSetCreatPropList array_layout(const std::vector<hsize_t>& chunk) {
  H5::DSetCreatPropList plist;
  if (chunk.empty()) return plist;
  plist.setChunk(static_cast<int>(chunk.size()), chunk.data());
  plist.setDeflate(4);
  return plist;
}

// Writes the array `data` (dimensions d, row-major) into the chunked dataset ds one whole chunk at a time (the
// chunks' grid in row-major order), polling the stop token (io/cancel.hpp) before each: deflating ~100 MB takes
// seconds, and one H5Dwrite of it could not be stopped.  Each chunk is written once and whole, so the dataset holds
// the same values, chunks and filter as after one write of the array.
template <class V>
void write_by_chunks(H5::DataSet& ds, const V* data, const std::vector<hsize_t>& d, const std::vector<hsize_t>& chunk) {
  const int rank = static_cast<int>(d.size());
  H5::DataSpace mem(rank, d.data()), file = ds.getSpace();
  std::vector<hsize_t> index(d.size(), 0), start(d.size()), count(d.size());
  for (;;) {
    check_stop();
    for (std::size_t i = 0; i < d.size(); ++i) {
      start[i] = index[i] * chunk[i];
      count[i] = std::min(chunk[i], d[i] - start[i]);
    }
    mem.selectHyperslab(H5S_SELECT_SET, count.data(), start.data());
    file.selectHyperslab(H5S_SELECT_SET, count.data(), start.data());
    ds.write(data, h5_type<V>(), mem, file);
    int i = rank - 1;  // the next chunk: an odometer over the chunk grid, last dimension fastest
    while (i >= 0 && (++index[static_cast<std::size_t>(i)]) * chunk[static_cast<std::size_t>(i)] >=
                         d[static_cast<std::size_t>(i)])
      index[static_cast<std::size_t>(i--)] = 0;
    if (i < 0) return;
  }
}

// The creation properties of an array the MPI ranks write (commands::RankRows): contiguous, allocated now and never
// filled, so that their collective write is plain MPI-IO into known offsets.  Not chunked and deflated as a single
// process writes it: parallel HDF5 1.10 funnels each filtered chunk through one rank, and every chunk would hold rows
// of several ranks.  The data are the same; only the file's layout differs.
H5::DSetCreatPropList ranks_layout() {
  H5::DSetCreatPropList plist;
  H5Pset_layout(plist.getId(), H5D_CONTIGUOUS);
  H5Pset_alloc_time(plist.getId(), H5D_ALLOC_TIME_EARLY);
  H5Pset_fill_time(plist.getId(), H5D_FILL_TIME_NEVER);
  return plist;
}

// How write_array lays out one array: a single process deflates the large ones in chunks; in a split sweep's file
// (rows written by the MPI ranks) rank 0 writes its own arrays contiguous, not deflated, since deflating there is
// work on rank 0 alone while every rank waits for its file (a per-r array of a sweep of millions of r values is
// most of what rank 0 does alone), and the arrays the ranks write are only made.
enum class Layout { deflated, contiguous, by_ranks };

// One array of the result as a dataset with its units, axes and description, laid out as `layout` says (a by_ranks
// array's view holds no data: only its shape and layout are made).
void write_array(H5::H5File& file, const core::ArrayView& a, Layout layout) {
  std::visit(
      [&](const auto* vec) {
        using V = typename std::decay_t<decltype(*vec)>::value_type;
        std::vector<hsize_t> d(a.dims.begin(), a.dims.end());
        std::size_t total = 1;
        for (auto x : a.dims) total *= x;
        const bool by_ranks = layout == Layout::by_ranks;
        if (!by_ranks && total != vec->size())
          throw std::logic_error(
              fmt::format("result array {}: {} elements for dims of {}", a.name, vec->size(), total));
        H5::DataSpace space(static_cast<int>(d.size()), d.data());
        const std::vector<hsize_t> chunk = layout == Layout::deflated ? array_chunk(d, total) : std::vector<hsize_t>{};
        H5::DataSet ds =
            file.createDataSet(a.name, h5_type<V>(), space, by_ranks ? ranks_layout() : array_layout(chunk));
        if (!by_ranks) {  // else the ranks write it
          if (!chunk.empty()) write_by_chunks(ds, vec->data(), d, chunk);
          else if (total > 0) ds.write(vec->data(), h5_type<V>());
        }
        string_attr(ds, "units", a.units);
        string_attr(ds, "axes", a.axes);
        string_attr(ds, "description", a.description);
      },
      a.data);
}

// An HDF5 file that its guard destroys quietly: after a failed write (disk full) its destructor's close fails too,
// and the error is reported once, by the caller.
struct QuietFile {
  H5::H5File* f = nullptr;
  ~QuietFile() {
    std::streambuf* old = std::cerr.rdbuf(nullptr);
    delete f;
    std::cerr.rdbuf(old);
  }
};

}  // namespace

// attributes -> arrays -> decimals and texts -> dimension scales; an HDF5 failure is one line naming the file.
void ResultFiles::h5(const core::Contents& c, const Attrs& attrs, const std::set<std::string>& by_ranks) {
  status_.insert(c.status.begin(), c.status.end());
  const std::string filename = name_ + ".h5";
  const fs::path p = staged(filename);
  H5::Exception::dontPrint();
  try {
    QuietFile guard;
    guard.f = new H5::H5File(p.string(), H5F_ACC_TRUNC);
    H5::H5File& file = *guard.f;
    write_root_attrs(file, attrs);
    for (const auto& a : c.arrays)
      write_array(file, a,
                  by_ranks.count(a.name) ? Layout::by_ranks
                  : by_ranks.empty()     ? Layout::deflated
                                         : Layout::contiguous);
    for (const auto* list : {&c.decimals, &c.texts})
      for (const auto& d : *list) string_dataset(file, d);
    write_status(file, c);
    attach_scales(file, c);
    file.close();
  } catch (const H5::Exception& e) {
    // Disk full, permission denied, a vanished folder: one line naming the file (the detail is HDF5's).
    std::error_code ec;
    const auto space = fs::space(tmp_, ec);
    const std::string cause = !ec && space.available < (1u << 20) ? "no space left on the device" : e.getDetailMsg();
    throw std::runtime_error(fmt::format("cannot write '{}': {}", final_path(filename).string(), cause));
  }
}

void ResultFiles::manifest(const Attrs& attrs, const std::string& command,
                           const std::vector<std::pair<std::string, std::vector<std::string>>>& args) {
  nlohmann::ordered_json j;
  for (const auto& [k, v] : attrs) std::visit([&](const auto& x) { j[k] = x; }, v);
  nlohmann::ordered_json req;
  req["command"] = command;
  nlohmann::ordered_json a = nlohmann::ordered_json::object();
  for (const auto& [k, vals] : args)
    a[k] = vals.size() == 1 ? nlohmann::ordered_json(vals[0]) : nlohmann::ordered_json(vals);
  req["args"] = a;
  j["request"] = req;
  text(name_ + ".json", j.dump(2) + "\n");
}

bool ResultFiles::plot(const std::string& script) { return plot(script, name_ + ".h5"); }

bool ResultFiles::plot(const std::string& script, const std::string& input) { return plot_inputs(script, {input}); }

bool ResultFiles::plot_inputs(const std::string& script, const std::vector<std::string>& inputs) {
  std::vector<std::string> args;
  for (const auto& f : inputs) args.push_back(staged(f).string());
  args.push_back(staged(name_ + ".png").string());
  const bool ran = run_plot(script, args);
  std::error_code ec;
  if (fs::exists(tmp_ / (name_ + ".png"), ec)) return ran;
  files_.erase(std::remove(files_.begin(), files_.end(), name_ + ".png"), files_.end());
  return false;
}

bool ResultFiles::plot_figures(const std::string& script, const std::vector<std::string>& inputs) {
  std::vector<std::string> args;
  for (const auto& f : inputs) args.push_back(staged(f).string());
  args.push_back(tmp_.string());
  const bool ran = run_plot(script, args);
  std::error_code ec;
  std::vector<std::string> images;
  for (const auto& e : fs::directory_iterator(tmp_, ec))
    if (e.path().extension() == ".png" || e.path().extension() == ".gif")
      images.push_back(e.path().filename().string());
  std::sort(images.begin(), images.end());  // a stable listing
  for (const auto& f : images) staged(f);
  return ran && !images.empty();
}

std::vector<fs::path> ResultFiles::commit() {
  check_stop();  // a run stopped while its files were staged commits nothing (io/cancel.hpp)
  std::error_code ec;
  fs::create_directories(out_, ec);
  if (ec || !fs::is_directory(out_)) throw_file_error("out: cannot create folder", out_, ec);
  // The manifest last: a folder whose manifest names a result holds all of that result's files.
  std::stable_partition(files_.begin(), files_.end(), [&](const std::string& f) { return f != name_ + ".json"; });
  std::vector<fs::path> done;
  for (const auto& f : files_) {
    fs::rename(tmp_ / f, out_ / f, ec);
    if (ec) throw_file_error("cannot move into place", out_ / f, ec);
    done.push_back(out_ / f);
  }
  committed_ = true;
  fs::remove_all(tmp_, ec);
  return done;
}

}  // namespace btob::io
