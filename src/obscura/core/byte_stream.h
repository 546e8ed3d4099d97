#pragma once
// Values packed into bytes and read back, for messages between the processes
// of a run (core/process_group.h): trivially copyable values, strings and
// vectors of them, in the machine's own representation (every process of a
// run is the same binary on the same kind of machine). A reader that runs
// past the end of its bytes is a bug in the protocol: InternalError.
#include <cstddef>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "obscura/core/check.h"

namespace obscura {

class ByteWriter {
 public:
  template <class T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes_.append(reinterpret_cast<const char*>(&value), sizeof(T));
  }
  void put_string(const std::string& s) {
    put<std::uint64_t>(s.size());
    bytes_.append(s);
  }
  template <class T>
  void put_vector(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    put<std::uint64_t>(v.size());
    bytes_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  const std::string& bytes() const { return bytes_; }
  std::string take() { return std::move(bytes_); }

 private:
  std::string bytes_;
};

class ByteReader {
 public:
  explicit ByteReader(const std::string& bytes) : bytes_(bytes) {}

  template <class T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    T value;
    std::memcpy(&value, take(sizeof(T)), sizeof(T));
    return value;
  }
  std::string get_string() {
    const auto n = get<std::uint64_t>();
    return std::string(take(n), n);
  }
  template <class T>
  std::vector<T> get_vector() {
    const auto n = get<std::uint64_t>();
    OBSCURA_CHECK_MSG(n <= remaining() / sizeof(T), "message shorter than its vector's length");
    std::vector<T> v(n);
    if (n > 0) std::memcpy(v.data(), take(n * sizeof(T)), n * sizeof(T));
    return v;
  }
  std::size_t remaining() const { return bytes_.size() - pos_; }
  bool done() const { return pos_ == bytes_.size(); }

 private:
  const char* take(std::size_t n) {
    OBSCURA_CHECK_MSG(n <= remaining(), "message shorter than what it says it holds");
    const char* p = bytes_.data() + pos_;
    pos_ += n;
    return p;
  }
  const std::string& bytes_;
  std::size_t pos_ = 0;
};

}  // namespace obscura
