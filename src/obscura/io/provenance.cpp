#include "obscura/io/provenance.h"

#include <fmt/format.h>
#include <openssl/evp.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <fstream>
#include <memory>

#include "obscura/core/error.h"
#include "obscura/core/version.h"

namespace obscura {
namespace {

struct MdCtxDeleter {
  void operator()(EVP_MD_CTX* ctx) const { EVP_MD_CTX_free(ctx); }
};
using MdCtx = std::unique_ptr<EVP_MD_CTX, MdCtxDeleter>;

// Incremental SHA-256 through the OpenSSL EVP interface (the low-level
// SHA256_* functions are deprecated in OpenSSL 3).
class Sha256 {
 public:
  Sha256() : ctx_(EVP_MD_CTX_new()) {
    if (!ctx_ || EVP_DigestInit_ex(ctx_.get(), EVP_sha256(), nullptr) != 1) {
      throw Error("OpenSSL: cannot initialise SHA-256");
    }
  }
  void update(const void* data, size_t size) {
    if (EVP_DigestUpdate(ctx_.get(), data, size) != 1)
      throw Error("OpenSSL: SHA-256 update failed");
  }
  std::string hex() {
    unsigned char digest[EVP_MAX_MD_SIZE];
    unsigned int size = 0;
    if (EVP_DigestFinal_ex(ctx_.get(), digest, &size) != 1) {
      throw Error("OpenSSL: SHA-256 final failed");
    }
    static constexpr char kHex[] = "0123456789abcdef";
    std::string out;
    out.reserve(2 * size);
    for (unsigned int i = 0; i < size; ++i) {
      out.push_back(kHex[digest[i] >> 4]);
      out.push_back(kHex[digest[i] & 0xf]);
    }
    return out;
  }

 private:
  MdCtx ctx_;
};

// Characters that no POSIX shell treats specially in an unquoted word.
bool shell_safe(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
         std::strchr("@%+=:,./-_", c) != nullptr;
}

std::string shell_quote(std::string_view arg) {
  bool safe = !arg.empty();
  for (char c : arg) safe = safe && shell_safe(c);
  if (safe) return std::string(arg);
  // Inside single quotes nothing is special except the quote itself, which is
  // written as '\'' (close, escaped quote, reopen).
  std::string out = "'";
  for (char c : arg) {
    if (c == '\'') {
      out += "'\\''";
    } else {
      out.push_back(c);
    }
  }
  return out + "'";
}

template <typename T>
T required(const nlohmann::json& value, const char* key) {
  auto it = value.find(key);
  if (it == value.end()) throw Error(fmt::format("provenance: missing key \"{}\"", key));
  try {
    return it->get<T>();
  } catch (const nlohmann::json::exception& e) {
    throw Error(fmt::format("provenance: key \"{}\": {}", key, e.what()));
  }
}

}  // namespace

nlohmann::json Provenance::to_json() const {
  nlohmann::json input_list = nlohmann::json::array();
  for (const InputHash& input : inputs) {
    input_list.push_back({{"path", input.path}, {"sha256", input.sha256}});
  }
  return {{"software", software}, {"version", version},   {"command_line", command_line},
          {"seed", seed},         {"inputs", input_list}, {"created_utc", created_utc}};
}

std::string Provenance::to_string() const { return to_json().dump(); }

Provenance Provenance::from_json(const nlohmann::json& value) {
  if (!value.is_object()) throw Error("provenance: expected a JSON object");
  Provenance p;
  p.software = required<std::string>(value, "software");
  p.version = required<std::string>(value, "version");
  p.command_line = required<std::string>(value, "command_line");
  p.seed = required<std::uint64_t>(value, "seed");
  p.created_utc = required<std::string>(value, "created_utc");
  auto inputs = required<nlohmann::json>(value, "inputs");
  if (!inputs.is_array()) throw Error("provenance: \"inputs\" must be an array");
  for (const auto& input : inputs) {
    p.inputs.push_back(
        {required<std::string>(input, "path"), required<std::string>(input, "sha256")});
  }
  return p;
}

std::string sha256_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw InputError(path.string(), "", std::string("cannot read file: ") + std::strerror(errno));
  Sha256 sha;
  char buffer[1 << 16];
  while (in) {
    in.read(buffer, sizeof buffer);
    sha.update(buffer, static_cast<size_t>(in.gcount()));
  }
  if (in.bad()) {
    throw InputError(path.string(), "", std::string("cannot read file: ") + std::strerror(errno));
  }
  return sha.hex();
}

std::string sha256_bytes(std::string_view bytes) {
  Sha256 sha;
  sha.update(bytes.data(), bytes.size());
  return sha.hex();
}

std::string join_command_line(int argc, const char* const* argv) {
  std::string out;
  for (int i = 0; i < argc; ++i) {
    if (i > 0) out.push_back(' ');
    out += shell_quote(argv[i] != nullptr ? argv[i] : "");
  }
  return out;
}

std::string utc_now_iso8601() {
  std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);  // gmtime() is not thread-safe
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return buffer;
}

Provenance make_provenance(std::string command_line, std::uint64_t seed,
                           const std::vector<std::filesystem::path>& inputs) {
  Provenance p;
  p.version = kVersion;
  p.command_line = std::move(command_line);
  p.seed = seed;
  for (const auto& input : inputs) p.inputs.push_back({input.string(), sha256_file(input)});
  p.created_utc = utc_now_iso8601();
  return p;
}

}  // namespace obscura
