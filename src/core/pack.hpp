// SPDX-License-Identifier: GPL-3.0-or-later
// Bytes of a plain struct and back, for sending a part of a sweep to another process (core/sweep.hpp).  A struct
// lists its members once, for both directions, like a request's fields():
//     template <class A> void members(A& a) { a(items, density, seconds); }
// Supported: arithmetic types and enums, std::string, std::vector of any supported type, fixed-size Eigen
// vectors and matrices, std::pair, and structs with members().  Values travel bitwise (doubles keep every bit,
// NaN payloads and signed zeros included); both ends are the same executable, so layout and endianness agree.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace btob::core {

namespace detail {
template <class T>
concept HasMembers = requires(T& t, int& a) {
  t.members(a);
};
template <class T>
concept FixedEigen = requires {
  T::RowsAtCompileTime;
  T::ColsAtCompileTime;
  typename T::Scalar;
}
&&(T::RowsAtCompileTime > 0) && (T::ColsAtCompileTime > 0);
template <class T> struct IsVector : std::false_type {};
template <class T, class A> struct IsVector<std::vector<T, A>> : std::true_type {};
template <class T> struct IsPair : std::false_type {};
template <class T, class U> struct IsPair<std::pair<T, U>> : std::true_type {};
}  // namespace detail

class Packer {
 public:
  std::vector<char> bytes;

  template <class... T> void operator()(const T&... v) { (put(v), ...); }

 private:
  void raw(const void* p, std::size_t n) {
    const char* c = static_cast<const char*>(p);
    bytes.insert(bytes.end(), c, c + n);
  }
  template <class T> void put(const T& v) {
    if constexpr (std::is_arithmetic_v<T> || std::is_enum_v<T>) {
      raw(&v, sizeof v);
    } else if constexpr (std::is_same_v<T, std::string>) {
      put(static_cast<std::uint64_t>(v.size()));
      raw(v.data(), v.size());
    } else if constexpr (detail::IsVector<T>::value) {
      put(static_cast<std::uint64_t>(v.size()));
      using E = typename T::value_type;
      if constexpr ((std::is_arithmetic_v<E> || std::is_enum_v<E>)&&!std::is_same_v<E, bool>)
        raw(v.data(), v.size() * sizeof(E));
      else
        for (const auto& e : v) put(static_cast<const E&>(e));
    } else if constexpr (detail::IsPair<T>::value) {
      put(v.first);
      put(v.second);
    } else if constexpr (detail::FixedEigen<T>) {
      for (int i = 0; i < v.size(); ++i) put(v.data()[i]);
    } else {
      static_assert(detail::HasMembers<T>, "core::Packer: give the type template <class A> void members(A&)");
      const_cast<T&>(v).members(*this);  // members() only passes references on; the packer reads them
    }
  }
};

class Unpacker {
 public:
  Unpacker(const char* data, std::size_t size) : p_(data), end_(data + size) {}
  template <class... T> void operator()(T&... v) { (get(v), ...); }
  bool done() const { return p_ == end_; }

 private:
  const char* p_;
  const char* end_;
  void raw(void* dst, std::size_t n) {
    if (static_cast<std::size_t>(end_ - p_) < n)
      throw std::runtime_error("core::Unpacker: message shorter than its contents");
    if (n == 0) return;  // an empty vector's data() may be null, which memcpy must not see (UBSan: nonnull)
    std::memcpy(dst, p_, n);
    p_ += n;
  }
  std::size_t count(std::size_t each) {
    std::uint64_t n = 0;
    get(n);
    if (each > 0 && n > static_cast<std::uint64_t>(end_ - p_) / each)
      throw std::runtime_error("core::Unpacker: a length beyond the message");
    return static_cast<std::size_t>(n);
  }
  template <class T> void get(T& v) {
    if constexpr (std::is_arithmetic_v<T> || std::is_enum_v<T>) {
      raw(&v, sizeof v);
    } else if constexpr (std::is_same_v<T, std::string>) {
      v.resize(count(1));
      raw(v.data(), v.size());
    } else if constexpr (detail::IsVector<T>::value) {
      using E = typename T::value_type;
      if constexpr ((std::is_arithmetic_v<E> || std::is_enum_v<E>)&&!std::is_same_v<E, bool>) {
        v.resize(count(sizeof(E)));
        raw(v.data(), v.size() * sizeof(E));
      } else {
        v.resize(count(1));  // every element takes at least a byte
        for (auto& e : v) {
          E x{};
          get(x);
          e = std::move(x);
        }
      }
    } else if constexpr (detail::IsPair<T>::value) {
      get(v.first);
      get(v.second);
    } else if constexpr (detail::FixedEigen<T>) {
      for (int i = 0; i < v.size(); ++i) get(v.data()[i]);
    } else {
      static_assert(detail::HasMembers<T>, "core::Unpacker: give the type template <class A> void members(A&)");
      v.members(*this);
    }
  }
};

// The bytes of v, and v from its bytes (throws std::runtime_error on a short or long message).
template <class T> std::vector<char> pack(const T& v) {
  Packer p;
  p(v);
  return std::move(p.bytes);
}
template <class T> T unpack(const std::vector<char>& bytes) {
  T v{};
  Unpacker u(bytes.data(), bytes.size());
  u(v);
  if (!u.done()) throw std::runtime_error("core::Unpacker: message longer than its contents");
  return v;
}

}  // namespace btob::core
