#include "obscura/io/vdb_chunk_check.h"

#include <blosc.h>
#include <fmt/format.h>
#include <zlib.h>

#include <vector>

namespace obscura::vdb_format {

std::optional<std::string> blosc_chunk_problem(const unsigned char* data, std::size_t cbytes,
                                               std::size_t expected_bytes, bool padded) {
  constexpr std::size_t kPadBytes = 128;  // points/StreamCompression.h BLOSC_PAD_BYTES
  if (cbytes < BLOSC_MIN_HEADER_LENGTH)
    return fmt::format("a blosc chunk of {} bytes is shorter than a blosc header", cbytes);
  std::size_t nbytes = 0, header_cbytes = 0, blocksize = 0;
  blosc_cbuffer_sizes(data, &nbytes, &header_cbytes, &blocksize);
  if (header_cbytes != cbytes)
    return fmt::format("a blosc chunk of {} bytes says it holds {}", cbytes, header_cbytes);
  const bool padded_to = padded && expected_bytes <= kPadBytes && nbytes == kPadBytes;
  if (nbytes != expected_bytes && !padded_to)
    return fmt::format("a blosc chunk decompresses to {} bytes where {} are expected", nbytes,
                       expected_bytes);
  if (blosc_cbuffer_validate(data, cbytes, &nbytes) != 0)
    return std::string("a blosc chunk has an invalid header");
  std::vector<unsigned char> out(nbytes);
  const int got = blosc_decompress_ctx(data, out.data(), out.size(), /*numinternalthreads=*/1);
  if (got < 0 || static_cast<std::size_t>(got) != nbytes)
    return fmt::format("a blosc chunk does not decompress (blosc returned {})", got);
  return std::nullopt;
}

std::optional<std::string> zip_chunk_problem(const unsigned char* data, std::size_t cbytes,
                                             std::size_t expected_bytes) {
  std::vector<unsigned char> out(expected_bytes);
  uLongf out_len = static_cast<uLongf>(out.size());
  const int status = uncompress(out.data(), &out_len, data, static_cast<uLong>(cbytes));
  if (status != Z_OK) return fmt::format("a zip chunk does not decompress ({})", zError(status));
  if (out_len != expected_bytes)
    return fmt::format("a zip chunk decompresses to {} bytes where {} are expected", out_len,
                       expected_bytes);
  return std::nullopt;
}

}  // namespace obscura::vdb_format
