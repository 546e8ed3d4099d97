#include "obscura/io/vtk_legacy_lexer.h"

#include <fmt/format.h>
#include <sys/stat.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstdlib>
#include <cstring>

#include "obscura/core/error.h"

namespace obscura::vtk_legacy {
namespace {

template <typename U>
U from_big_endian(const unsigned char* p) {
  U v = 0;
  for (std::size_t i = 0; i < sizeof(U); ++i) v = static_cast<U>((v << 8) | p[i]);
  return v;
}

}  // namespace

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::optional<ValueType> parse_value_type(std::string_view token) {
  const std::string t = lower(token);
  struct Entry {
    const char* name;
    ValueKind kind;
    int bytes;
  };
  static constexpr Entry kTypes[] = {
      {"bit", ValueKind::kBit, 0},
      {"char", ValueKind::kSigned, 1},
      {"signed_char", ValueKind::kSigned, 1},
      {"unsigned_char", ValueKind::kUnsigned, 1},
      {"short", ValueKind::kSigned, 2},
      {"unsigned_short", ValueKind::kUnsigned, 2},
      {"int", ValueKind::kSigned, 4},
      {"unsigned_int", ValueKind::kUnsigned, 4},
      {"vtkidtype", ValueKind::kSigned, 4},
      {"long", ValueKind::kSigned, 8},
      {"unsigned_long", ValueKind::kUnsigned, 8},
      {"vtktypeint64", ValueKind::kSigned, 8},
      {"vtktypeuint64", ValueKind::kUnsigned, 8},
      {"float", ValueKind::kFloat, 4},
      {"double", ValueKind::kDouble, 8},
  };
  for (const Entry& e : kTypes)
    if (t == e.name) return ValueType{t, e.kind, e.bytes};
  return std::nullopt;
}

std::string decode_name(std::string_view s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '%' && i + 2 < s.size() && std::isxdigit(static_cast<unsigned char>(s[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(s[i + 2]))) {
      out += static_cast<char>(std::stoi(std::string(s.substr(i + 1, 2)), nullptr, 16));
      i += 2;
    } else {
      out += s[i];
    }
  }
  return out;
}

std::string encode_name(std::string_view s) {
  std::string out;
  for (char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (c <= ' ' || c >= 0x7f || c == '%' || c == '"')
      out += fmt::format("%{:02X}", static_cast<unsigned>(c));
    else
      out += ch;
  }
  return out;
}

double binary_value(const ValueType& t, const unsigned char* p) {
  switch (t.kind) {
    case ValueKind::kFloat:
      return std::bit_cast<float>(from_big_endian<std::uint32_t>(p));
    case ValueKind::kDouble:
      return std::bit_cast<double>(from_big_endian<std::uint64_t>(p));
    case ValueKind::kUnsigned:
      switch (t.bytes) {
        case 1:
          return p[0];
        case 2:
          return from_big_endian<std::uint16_t>(p);
        case 4:
          return from_big_endian<std::uint32_t>(p);
        default:
          return static_cast<double>(from_big_endian<std::uint64_t>(p));
      }
    case ValueKind::kSigned:
      switch (t.bytes) {
        case 1:
          return static_cast<std::int8_t>(p[0]);
        case 2:
          return static_cast<std::int16_t>(from_big_endian<std::uint16_t>(p));
        case 4:
          return static_cast<std::int32_t>(from_big_endian<std::uint32_t>(p));
        default:
          return static_cast<double>(static_cast<std::int64_t>(from_big_endian<std::uint64_t>(p)));
      }
    case ValueKind::kBit:
      break;
  }
  return 0.0;
}

std::optional<double> parse_ascii_value(const ValueType& t, std::string_view s) {
  if (!s.empty() && s[0] == '+') s.remove_prefix(1);
  const char* b = s.data();
  const char* e = s.data() + s.size();
  if (t.kind == ValueKind::kFloat || t.kind == ValueKind::kDouble) {
    if (t.kind == ValueKind::kFloat) {
      float f = 0;
      auto [ptr, ec] = std::from_chars(b, e, f);
      if (ec == std::errc() && ptr == e) return f;
      if (ec != std::errc::result_out_of_range) return std::nullopt;
    } else {
      double d = 0;
      auto [ptr, ec] = std::from_chars(b, e, d);
      if (ec == std::errc() && ptr == e) return d;
      if (ec != std::errc::result_out_of_range) return std::nullopt;
    }
    // Out of range (underflow to zero or overflow to infinity): strtod gives
    // the limit value, which the range checks later judge.
    const std::string copy(s);
    char* end = nullptr;
    const double d = std::strtod(copy.c_str(), &end);
    if (end != copy.c_str() + copy.size()) return std::nullopt;
    return t.kind == ValueKind::kFloat ? static_cast<double>(static_cast<float>(d)) : d;
  }
  if (t.kind == ValueKind::kUnsigned) {
    unsigned long long u = 0;
    auto [ptr, ec] = std::from_chars(b, e, u);
    if (ec == std::errc() && ptr == e) return static_cast<double>(u);
    return std::nullopt;
  }
  long long v = 0;
  auto [ptr, ec] = std::from_chars(b, e, v);
  if (ec == std::errc() && ptr == e) return static_cast<double>(v);
  return std::nullopt;
}

Lexer::Lexer(const std::filesystem::path& path, std::string file) : file_(std::move(file)) {
  f_ = std::fopen(path.c_str(), "rb");
  if (f_ == nullptr)
    throw InputError(file_, "", fmt::format("cannot open: {}", std::strerror(errno)));
  struct stat st {};
  if (::fstat(::fileno(f_), &st) != 0 || !S_ISREG(st.st_mode)) {
    std::fclose(f_);
    throw InputError(file_, "", "not a regular file");
  }
  file_size_ = static_cast<std::uint64_t>(st.st_size);
}

Lexer::~Lexer() { std::fclose(f_); }

std::string Lexer::where(long line, std::uint64_t offset) {
  return line > 0 ? fmt::format("line {}", line) : fmt::format("byte {}", offset);
}

bool Lexer::next(Token& t) {
  if (pushed_) {
    t = std::move(*pushed_);
    pushed_.reset();
    return true;
  }
  int c = get();
  while (c != EOF && std::isspace(c)) c = get();
  if (c == EOF) return false;
  t.line = lines_valid_ ? line_ : 0;
  last_line_ = line_;
  t.offset = offset() - 1;
  t.text.clear();
  while (c != EOF && !std::isspace(c)) {
    t.text += static_cast<char>(c);
    c = get();
  }
  if (c == '\n') {  // unread it: get() has just taken it from the buffer
    --pos_;
    --line_;
  }
  return true;
}

std::optional<std::string> Lexer::read_line() {
  int c = get();
  if (c == EOF) return std::nullopt;
  std::string s;
  while (c != EOF && c != '\n') {
    s += static_cast<char>(c);
    c = get();
  }
  if (!s.empty() && s.back() == '\r') s.pop_back();
  return s;
}

void Lexer::finish_line() {
  int c = get();
  while (c != EOF && c != '\n') c = get();
}

std::size_t Lexer::read(unsigned char* dst, std::size_t n) {
  lines_valid_ = false;
  std::size_t done = 0;
  while (done < n) {
    if (pos_ == len_ && !fill()) break;
    const std::size_t k = std::min(n - done, len_ - pos_);
    std::memcpy(dst + done, buf_.data() + pos_, k);
    pos_ += k;
    done += k;
  }
  return done;
}

void Lexer::skip(std::uint64_t n) {
  lines_valid_ = false;
  const std::uint64_t in_buffer = len_ - pos_;
  if (n <= in_buffer) {
    pos_ += static_cast<std::size_t>(n);
    return;
  }
  const std::uint64_t target = offset() + n;
  if (::fseeko(f_, static_cast<off_t>(target), SEEK_SET) != 0)
    throw InputError(file_, where(), fmt::format("cannot seek: {}", std::strerror(errno)));
  buf_start_ = target;
  pos_ = len_ = 0;
}

int Lexer::get() {
  if (pos_ == len_ && !fill()) return EOF;
  const int c = buf_[pos_++];
  if (c == '\n') ++line_;
  return c;
}

bool Lexer::fill() {
  buf_start_ += len_;
  pos_ = 0;
  len_ = std::fread(buf_.data(), 1, buf_.size(), f_);
  if (len_ == 0 && std::ferror(f_))
    throw InputError(file_, where(), fmt::format("read error: {}", std::strerror(errno)));
  return len_ > 0;
}

}  // namespace obscura::vtk_legacy
