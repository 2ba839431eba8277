#include "io/lzf.hpp"

#include <algorithm>

namespace sgnlf::io {
namespace {

constexpr size_t kMaxLiteral = 32;         // control byte 0..31
constexpr size_t kMaxOffset = 8192;        // 13 bits + 1
constexpr size_t kMaxMatch = 7 + 255 + 2;  // long reference: 7 + extra byte, + 2
constexpr int kHashBits = 14;

uint32_t hash3(const uint8_t* p) {
  const uint32_t v = uint32_t(p[0]) << 16 | uint32_t(p[1]) << 8 | p[2];
  return (v * 2654435761u) >> (32 - kHashBits);
}

void flush_literals(const uint8_t* in, size_t from, size_t to, std::vector<uint8_t>& out) {
  while (from < to) {
    const size_t run = std::min(kMaxLiteral, to - from);
    out.push_back(uint8_t(run - 1));
    out.insert(out.end(), in + from, in + from + run);
    from += run;
  }
}

}  // namespace

std::vector<uint8_t> lzf_compress(const uint8_t* in, size_t n) {
  std::vector<uint8_t> out;
  out.reserve(n + n / kMaxLiteral + 1);
  std::vector<size_t> table(size_t(1) << kHashBits, 0);  // position + 1 of the last 3-byte key
  size_t ip = 0, lit = 0;
  while (ip + 3 <= n) {
    const uint32_t h = hash3(in + ip);
    const size_t cand = table[h];
    table[h] = ip + 1;
    if (cand > 0 && ip - (cand - 1) <= kMaxOffset && std::equal(in + ip, in + ip + 3, in + cand - 1)) {
      const size_t ref = cand - 1, max_len = std::min(kMaxMatch, n - ip);
      size_t len = 3;
      while (len < max_len && in[ref + len] == in[ip + len]) ++len;
      flush_literals(in, lit, ip, out);
      const size_t off = ip - ref - 1, l = len - 2;
      if (l < 7) {
        out.push_back(uint8_t(l << 5 | off >> 8));
      } else {
        out.push_back(uint8_t(7 << 5 | off >> 8));
        out.push_back(uint8_t(l - 7));
      }
      out.push_back(uint8_t(off & 0xff));
      ip += len;
      lit = ip;
    } else {
      ++ip;
    }
  }
  flush_literals(in, lit, n, out);
  return out;
}

bool lzf_decompress(const uint8_t* in, size_t n, uint8_t* out, size_t out_size, std::string& error,
                    size_t& offset) {
  size_t ip = 0, op = 0;
  auto fail = [&](const std::string& what, size_t at) {
    error = what;
    offset = at;
    return false;
  };
  while (ip < n) {
    const size_t chunk = ip;
    const unsigned c = in[ip++];
    if (c < kMaxLiteral) {
      const size_t run = c + 1;
      if (run > n - ip) return fail("literal run of " + std::to_string(run) + " bytes past the end of the stream", chunk);
      if (run > out_size - op) return fail("literal run overflows the uncompressed size", chunk);
      std::copy(in + ip, in + ip + run, out + op);
      ip += run;
      op += run;
      continue;
    }
    size_t len = c >> 5;
    if (len == 7) {
      if (ip >= n) return fail("back reference cut off by the end of the stream", chunk);
      len += in[ip++];
    }
    if (ip >= n) return fail("back reference cut off by the end of the stream", chunk);
    const size_t back = ((size_t(c & 31) << 8) | in[ip++]) + 1;
    len += 2;
    if (back > op) return fail("back reference " + std::to_string(back) + " bytes before the start of the output", chunk);
    if (len > out_size - op) return fail("back reference overflows the uncompressed size", chunk);
    for (size_t k = 0; k < len; ++k, ++op) out[op] = out[op - back];
  }
  if (op != out_size)
    return fail("stream ends after " + std::to_string(op) + " of " + std::to_string(out_size) + " uncompressed bytes", n);
  return true;
}

}  // namespace sgnlf::io
