// LZF (Marc Lehmann's liblzf format), the compression of PCD's `DATA binary_compressed`.
// The stream is a sequence of chunks, each led by a control byte c:
//   c < 32        literal run: the next c + 1 bytes are copied to the output;
//   c >= 32       back reference: length L = c >> 5 (when L == 7, L += next byte), offset
//                 O = ((c & 31) << 8 | next byte) + 1; copies L + 2 bytes from O bytes back
//                 (byte by byte, so a reference may overlap the bytes it produces).
// The decoder is strict: every chunk must be complete, every reference inside the output so
// far, and the output exactly the expected size; anything else is a corrupt stream.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace sgnlf::io {

// Largest expansion of LZF: a 3-byte reference yields at most 264 bytes, so a stream of n bytes
// decodes to at most 88·n. Readers check a claimed size against it before allocating.
constexpr size_t kLzfMaxRatio = 88;

// Compresses `n` bytes (greedy matching over an 8 KiB window). Never fails: incompressible
// input grows by one control byte per 32 bytes.
std::vector<uint8_t> lzf_compress(const uint8_t* in, size_t n);

// Decodes `n` bytes into exactly `out_size` bytes. On a corrupt stream returns false and sets
// `error` to what was wrong and `offset` to its position in the compressed stream.
bool lzf_decompress(const uint8_t* in, size_t n, uint8_t* out, size_t out_size, std::string& error,
                    size_t& offset);

}  // namespace sgnlf::io
