// SPDX-License-Identifier: GPL-3.0-or-later
// The ergodic decomposition of Ulam's matrix: strongly connected components (Tarjan), the closed ones among them
// numbered by their first box, and each closed class's period.
#include "transfer/detail.hpp"

#include <algorithm>
#include <cstdlib>
#include <numeric>

namespace btob::transfer {

using detail::at;

namespace {

// Tarjan's algorithm, iterative (the graph has up to ~10^6 vertices: no recursion).  The component of every box,
// numbered in the order Tarjan closes them.
class Tarjan {
 public:
  explicit Tarjan(const UlamMatrix& P)
      : P_(P), index_(at(P.n), -1), low_(at(P.n), 0), on_stack_(at(P.n), 0), component_(at(P.n), -1) {
    for (long box = 0; box < P.n; ++box)
      if (index_[at(box)] < 0) visit_from(box);
  }
  std::vector<int> component() && { return std::move(component_); }
  int components() const { return components_; }

 private:
  const UlamMatrix& P_;
  std::vector<long> index_, low_, stack_;
  std::vector<char> on_stack_;
  std::vector<int> component_;
  std::vector<std::pair<long, int>> call_;  // (vertex, next edge position)
  long counter_ = 0;
  int components_ = 0;

  void open(long v) {
    index_[at(v)] = low_[at(v)] = counter_++;
    stack_.push_back(v);
    on_stack_[at(v)] = 1;
    call_.push_back({v, P_.row_ptr[at(v)]});
  }
  // v's lowlink is its own index: pop its component off the stack.
  void close(long v) {
    long w;
    do {
      w = stack_.back();
      stack_.pop_back();
      on_stack_[at(w)] = 0;
      component_[at(w)] = components_;
    } while (w != v);
    ++components_;
  }
  void visit_from(long root) {
    open(root);
    while (!call_.empty()) {
      auto& [v, e] = call_.back();
      if (e < P_.row_ptr[at(v + 1)]) {
        const long w = P_.col[at(e++)];
        if (index_[at(w)] < 0) open(w);
        else if (on_stack_[at(w)]) low_[at(v)] = std::min(low_[at(v)], index_[at(w)]);
        continue;
      }
      const long done = v;
      if (low_[at(done)] == index_[at(done)]) close(done);
      call_.pop_back();
      if (!call_.empty()) {
        const long parent = call_.back().first;
        low_[at(parent)] = std::min(low_[at(parent)], low_[at(done)]);
      }
    }
  }
};

// The closed components (no transition leaves them; an empty row, whose samples all left the chart, is not
// closed), ordered by their first box (deterministic, independent of the traversal); their sizes and first boxes.
struct ClosedComponents {
  std::vector<int> order;             // closed components, by first box
  std::vector<long> first_box, size;  // per component
};
ClosedComponents closed_components(const UlamMatrix& P, const std::vector<int>& scc, int components) {
  ClosedComponents out;
  std::vector<char> closed(static_cast<std::size_t>(components), 1);
  out.first_box.assign(static_cast<std::size_t>(components), -1);
  out.size.assign(static_cast<std::size_t>(components), 0);
  for (std::size_t i = 0; i < scc.size(); ++i) {
    const auto c = static_cast<std::size_t>(scc[i]);
    if (out.first_box[c] < 0) out.first_box[c] = static_cast<long>(i);
    ++out.size[c];
    if (P.row_ptr[i] == P.row_ptr[i + 1]) closed[c] = 0;
    for (int e = P.row_ptr[i]; e < P.row_ptr[i + 1]; ++e)
      if (scc[at(P.col[at(e)])] != scc[i]) closed[c] = 0;
  }
  for (int c = 0; c < components; ++c)
    if (closed[static_cast<std::size_t>(c)]) out.order.push_back(c);
  std::sort(out.order.begin(), out.order.end(), [&](int x, int y) {
    return out.first_box[static_cast<std::size_t>(x)] < out.first_box[static_cast<std::size_t>(y)];
  });
  return out;
}

// Period of the class holding `first`: gcd of level(u) + 1 - level(v) over its edges, levels from a breadth-first
// search of the class (`level`: -1 for unvisited boxes, shared by the classes, which are disjoint).
int class_period(const UlamMatrix& P, long first, std::vector<long>& level) {
  std::vector<long> queue{first};
  level[at(first)] = 0;
  long g = 0;
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const long u = queue[head];
    for (int e = P.row_ptr[at(u)]; e < P.row_ptr[at(u + 1)]; ++e) {
      const long v = P.col[at(e)];
      if (level[at(v)] < 0) {
        level[at(v)] = level[at(u)] + 1;
        queue.push_back(v);
      } else {
        g = std::gcd(g, std::labs(level[at(u)] + 1 - level[at(v)]));
      }
    }
  }
  return g == 0 ? 1 : static_cast<int>(g);
}

}  // namespace

Decomposition decompose(const UlamMatrix& P) {
  Decomposition d;
  Tarjan tarjan(P);
  d.components = tarjan.components();
  d.scc = std::move(tarjan).component();
  const ClosedComponents closed = closed_components(P, d.scc, d.components);
  std::vector<int> class_id(static_cast<std::size_t>(d.components), 0);
  for (std::size_t k = 0; k < closed.order.size(); ++k)
    class_id[static_cast<std::size_t>(closed.order[k])] = static_cast<int>(k + 1);
  d.class_of_box.assign(at(P.n), 0);
  for (std::size_t i = 0; i < d.class_of_box.size(); ++i)
    d.class_of_box[i] = static_cast<std::uint32_t>(class_id[static_cast<std::size_t>(d.scc[i])]);
  d.classes.resize(closed.order.size());
  std::vector<long> level(at(P.n), -1);
  for (std::size_t k = 0; k < closed.order.size(); ++k) {
    const auto c = static_cast<std::size_t>(closed.order[k]);
    d.classes[k].boxes = closed.size[c];
    d.classes[k].period = class_period(P, closed.first_box[c], level);
  }
  return d;
}

}  // namespace btob::transfer
