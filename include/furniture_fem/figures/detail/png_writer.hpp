#pragma once
// PNG encoding without zlib: CRC-32, Adler-32, a zlib stream of stored (uncompressed) deflate blocks
// or of one fixed-Huffman block with a small LZ77 matcher, and the PNG chunk layout (RFC 1950/1951,
// PNG spec). Plots are mostly flat colour, so the fixed-Huffman path shrinks a 1000x600 figure from
// 1.8 MB to a few tens of kB; the stored path exists because it is trivially verifiable.
#ifndef FURNITURE_FEM_FIGURES_INTERNAL
#error "furniture_fem/figures/detail/png_writer.hpp is internal: include <furniture_fem/figures/plot.hpp>"
#endif
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace furniture_fem::detail::png {

// CRC-32 (ISO 3309, reflected polynomial 0xEDB88320) as used by PNG chunks and gzip.
inline constexpr std::array<std::uint32_t, 256> crc_table = [] {
  std::array<std::uint32_t, 256> t{};
  for (std::uint32_t n = 0; n < 256; ++n) {
    std::uint32_t c = n;
    for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    t[n] = c;
  }
  return t;
}();

// Running form: pass the previous result as `crc` to continue over split data.
inline std::uint32_t crc32(const std::uint8_t* data, std::size_t n, std::uint32_t crc = 0) {
  crc ^= 0xFFFFFFFFu;
  for (std::size_t i = 0; i < n; ++i) crc = crc_table[(crc ^ data[i]) & 0xFFu] ^ (crc >> 8);
  return crc ^ 0xFFFFFFFFu;
}

inline std::uint32_t adler32(const std::uint8_t* data, std::size_t n, std::uint32_t adler = 1) {
  constexpr std::uint32_t mod = 65521;
  std::uint32_t a = adler & 0xFFFFu, b = adler >> 16;
  // 5552 is the largest block for which b cannot overflow 32 bits before the modulo (zlib's NMAX).
  while (n > 0) {
    std::size_t block = n < 5552 ? n : 5552;
    n -= block;
    while (block--) {
      a += *data++;
      b += a;
    }
    a %= mod;
    b %= mod;
  }
  return (b << 16) | a;
}

inline void put_be32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  out.push_back(std::uint8_t(v >> 24));
  out.push_back(std::uint8_t(v >> 16));
  out.push_back(std::uint8_t(v >> 8));
  out.push_back(std::uint8_t(v));
}

// Deflate writes bits least-significant first; Huffman codes go most-significant first, so callers
// reverse them before put().
class BitWriter {
 public:
  explicit BitWriter(std::vector<std::uint8_t>& out) : out_(out) {}
  void put(std::uint32_t bits, int n) {
    acc_ |= std::uint64_t(bits) << nbits_;
    nbits_ += n;
    while (nbits_ >= 8) {
      out_.push_back(std::uint8_t(acc_));
      acc_ >>= 8;
      nbits_ -= 8;
    }
  }
  void put_huffman(std::uint32_t code, int n) { put(reverse(code, n), n); }
  void finish() {
    if (nbits_ > 0) out_.push_back(std::uint8_t(acc_));
    acc_ = 0;
    nbits_ = 0;
  }
  static std::uint32_t reverse(std::uint32_t code, int n) {
    std::uint32_t r = 0;
    for (int i = 0; i < n; ++i) r |= ((code >> i) & 1u) << (n - 1 - i);
    return r;
  }

 private:
  std::vector<std::uint8_t>& out_;
  std::uint64_t acc_ = 0;
  int nbits_ = 0;
};

// RFC 1951 3.2.5 length and distance tables.
inline constexpr std::array<std::uint16_t, 29> length_base = {
    3, 4, 5, 6, 7, 8, 9, 10, 11, 13, 15, 17, 19, 23, 27, 31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
inline constexpr std::array<std::uint8_t, 29> length_extra = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,
                                                              2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
inline constexpr std::array<std::uint16_t, 30> dist_base = {
    1, 2, 3, 4, 5, 7, 9, 13, 17, 25, 33, 49, 65, 97, 129, 193, 257, 385, 513, 769, 1025, 1537, 2049, 3073,
    4097, 6145, 8193, 12289, 16385, 24577};
inline constexpr std::array<std::uint8_t, 30> dist_extra = {0, 0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 6,
                                                            6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};

// Fixed literal/length code of RFC 1951 3.2.6.
inline void put_fixed_symbol(BitWriter& bw, int sym) {
  if (sym < 144) bw.put_huffman(0x30u + sym, 8);
  else if (sym < 256) bw.put_huffman(0x190u + (sym - 144), 9);
  else if (sym < 280) bw.put_huffman(std::uint32_t(sym - 256), 7);
  else bw.put_huffman(0xC0u + (sym - 280), 8);
}

inline void put_match(BitWriter& bw, int length, int distance) {
  int li = 28;
  while (length_base[li] > length) --li;
  put_fixed_symbol(bw, 257 + li);
  if (length_extra[li]) bw.put(std::uint32_t(length - length_base[li]), length_extra[li]);
  int di = 29;
  while (dist_base[di] > distance) --di;
  bw.put_huffman(std::uint32_t(di), 5);
  if (dist_extra[di]) bw.put(std::uint32_t(distance - dist_base[di]), dist_extra[di]);
}

// Raw deflate, one fixed-Huffman block. Greedy LZ77 that tries the distances that pay off in a raster
// (previous byte, previous pixel, the same place one row up) plus the last position with the same
// 3-byte hash. `row_stride` is the filtered scanline length (1 + 3 * width).
inline void deflate_fixed(const std::vector<std::uint8_t>& in, std::size_t row_stride,
                          std::vector<std::uint8_t>& out) {
  BitWriter bw(out);
  bw.put(1, 1);  // BFINAL
  bw.put(1, 2);  // BTYPE = 01, fixed Huffman
  constexpr std::size_t window = 32768, max_len = 258, hash_bits = 15;
  std::vector<std::uint32_t> head(std::size_t(1) << hash_bits, 0);  // position + 1, 0 = empty
  const std::size_t n = in.size();
  auto hash = [&](std::size_t i) {
    std::uint32_t v = std::uint32_t(in[i]) | std::uint32_t(in[i + 1]) << 8 | std::uint32_t(in[i + 2]) << 16;
    return (v * 2654435761u) >> (32 - hash_bits);
  };
  auto insert = [&](std::size_t i) {
    if (i + 2 < n) head[hash(i)] = std::uint32_t(i + 1);
  };
  std::size_t i = 0;
  while (i < n) {
    std::size_t best_len = 0, best_dist = 0;
    if (i + 2 < n) {
      const std::size_t limit = std::min(max_len, n - i);
      std::array<std::size_t, 4> cand = {1, 3, row_stride, 0};
      if (std::uint32_t h = head[hash(i)]; h != 0) cand[3] = i - (h - 1);
      for (std::size_t d : cand) {
        if (d == 0 || d > i || d > window) continue;
        const std::uint8_t* a = &in[i];
        const std::uint8_t* b = &in[i - d];
        std::size_t len = 0;
        while (len < limit && a[len] == b[len]) ++len;
        if (len > best_len) {
          best_len = len;
          best_dist = d;
          if (len == limit) break;
        }
      }
    }
    if (best_len >= 3) {
      put_match(bw, int(best_len), int(best_dist));
      for (std::size_t k = 0; k < best_len; ++k) insert(i + k);
      i += best_len;
    } else {
      put_fixed_symbol(bw, in[i]);
      insert(i);
      ++i;
    }
  }
  put_fixed_symbol(bw, 256);  // end of block
  bw.finish();
}

// Raw deflate made of stored blocks (at most 65535 bytes each).
inline void deflate_stored(const std::vector<std::uint8_t>& in, std::vector<std::uint8_t>& out) {
  std::size_t pos = 0;
  do {
    const std::size_t len = std::min<std::size_t>(65535, in.size() - pos);
    const bool final = pos + len == in.size();
    out.push_back(final ? 1 : 0);  // BFINAL, BTYPE = 00; the rest of the byte is padding
    out.push_back(std::uint8_t(len));
    out.push_back(std::uint8_t(len >> 8));
    out.push_back(std::uint8_t(~len));
    out.push_back(std::uint8_t(~len >> 8));
    out.insert(out.end(), in.begin() + std::ptrdiff_t(pos), in.begin() + std::ptrdiff_t(pos + len));
    pos += len;
  } while (pos < in.size());
}

// zlib wrapper: CMF 0x78 (deflate, 32 KiB window), FLG 0x01 (checksum bits only), data, Adler-32.
inline std::vector<std::uint8_t> zlib_compress(const std::vector<std::uint8_t>& in, bool compress,
                                               std::size_t row_stride) {
  std::vector<std::uint8_t> out = {0x78, 0x01};
  out.reserve(compress ? in.size() / 8 + 64 : in.size() + in.size() / 65535 * 5 + 16);
  if (compress) deflate_fixed(in, row_stride, out);
  else deflate_stored(in, out);
  put_be32(out, adler32(in.data(), in.size()));
  return out;
}

inline void put_chunk(std::vector<std::uint8_t>& out, const char type[4], const std::uint8_t* data,
                      std::size_t n) {
  put_be32(out, std::uint32_t(n));
  const std::size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data, data + n);
  put_be32(out, crc32(&out[start], n + 4));
}

}  // namespace furniture_fem::detail::png
