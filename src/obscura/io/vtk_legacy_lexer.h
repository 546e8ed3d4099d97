#pragma once
// The lexical layer of VTK legacy files (VTK File Formats, "Simple Legacy
// Formats"), shared by the STRUCTURED_POINTS reader and writer
// (io/vtk_structured_points.h): data types and their sizes in BINARY files,
// the %-encoding of array names, value parsing, and a buffered tokeniser that
// knows where it is in the file. Internal to io/.
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace obscura::vtk_legacy {

// Data types of the legacy format and their size in BINARY files. The sizes
// follow VTK's own reader (IO/Legacy/vtkDataReader.cxx, ReadArray): vtkIdType
// is written as a 4-byte int, long as the platform long (8 bytes on 64-bit
// Linux and macOS, where these files are made), bit arrays packed 8 per byte.
enum class ValueKind { kBit, kSigned, kUnsigned, kFloat, kDouble };
struct ValueType {
  std::string name;  // as in the file, lower case
  ValueKind kind = ValueKind::kFloat;
  int bytes = 4;
};

std::string lower(std::string_view s);

// The type named by a token (case-insensitive), or nullopt.
std::optional<ValueType> parse_value_type(std::string_view token);

// VTK %-encodes the characters of array names that would break the
// whitespace-separated header (vtkDataWriter::EncodeString / DecodeString).
std::string decode_name(std::string_view s);
std::string encode_name(std::string_view s);

// One BINARY value at p (big-endian, as every VTK legacy file stores them,
// whatever the machine that wrote it), converted to double. Not for bit arrays.
double binary_value(const ValueType& t, const unsigned char* p);

// One ASCII value of type t, or nullopt if the token is not one. Floats are
// parsed as float so that a float printed in its shortest round-trip form
// reads back bit for bit; values beyond the type's range become 0 or ±inf.
std::optional<double> parse_ascii_value(const ValueType& t, std::string_view s);

struct Token {
  std::string text;
  long line = 0;  // 0: after binary data, use the offset
  std::uint64_t offset = 0;
};

// A buffered reader over the file that tokenises the ASCII parts and reads
// the BINARY blocks, and knows where it is: line numbers while the file is
// text, byte offsets once a binary block has been crossed (line numbers mean
// nothing after raw bytes, which may contain newlines). Throws InputError
// naming `file` if the file cannot be opened or read.
class Lexer {
 public:
  Lexer(const std::filesystem::path& path, std::string file);
  ~Lexer();
  Lexer(const Lexer&) = delete;
  Lexer& operator=(const Lexer&) = delete;

  const std::string& file() const { return file_; }
  std::uint64_t offset() const { return buf_start_ + pos_; }
  std::uint64_t file_size() const { return file_size_; }
  std::uint64_t remaining() const { return file_size_ - offset(); }

  // "line N" while the file is text so far, "byte N" after binary data.
  std::string where() const { return where(lines_valid_ ? line_ : 0, offset()); }
  static std::string where(long line, std::uint64_t offset);
  static std::string where(const Token& t) { return where(t.line, t.offset); }
  // At end of file: the line of the last token (a final newline does not
  // start a line anyone can see), or the file size after binary data.
  std::string where_end() const { return where(lines_valid_ ? last_line_ : 0, offset()); }

  // Next whitespace-separated token; false at end of file. A token's newline
  // is left unread, so that finish_line() after it stops at the right place.
  bool next(Token& t);
  // The next call to next() returns `t` again.
  void push_back(Token t) { pushed_ = std::move(t); }

  // The rest of the current line (without '\n' and a trailing '\r'); nullopt
  // at end of file.
  std::optional<std::string> read_line();

  // Binary data starts on the line after its header: VTK's reader discards
  // the rest of the header line ("suck up newline" in vtkReadBinaryData).
  void finish_line();

  // Copies up to n bytes; returns how many were read.
  std::size_t read(unsigned char* dst, std::size_t n);
  // Skips n bytes of binary data; the caller has checked that they exist.
  void skip(std::uint64_t n);

 private:
  int get();
  bool fill();

  std::string file_;
  std::FILE* f_ = nullptr;
  std::uint64_t file_size_ = 0;
  std::array<unsigned char, 1 << 16> buf_{};
  std::size_t pos_ = 0, len_ = 0;
  std::uint64_t buf_start_ = 0;  // file offset of buf_[0]
  long line_ = 1;
  long last_line_ = 1;
  bool lines_valid_ = true;
  std::optional<Token> pushed_;
};

}  // namespace obscura::vtk_legacy
