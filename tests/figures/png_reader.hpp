#pragma once
// A small PNG reader for the tests, written independently of the encoder: bitwise CRC-32, plain
// Adler-32, an inflater for stored and fixed-Huffman blocks whose length/distance tables are derived
// from the RFC 1951 rules rather than copied. Throws std::runtime_error on anything malformed.
#include <cstdint>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

namespace png_test {

inline std::vector<std::uint8_t> read_bytes(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw std::runtime_error("cannot open " + path);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

inline std::uint32_t crc32_bitwise(const std::uint8_t* p, std::size_t n) {
  std::uint32_t c = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < n; ++i) {
    c ^= p[i];
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
  }
  return ~c;
}

inline std::uint32_t adler32_plain(const std::uint8_t* p, std::size_t n) {
  std::uint64_t a = 1, b = 0;
  for (std::size_t i = 0; i < n; ++i) {
    a = (a + p[i]) % 65521;
    b = (b + a) % 65521;
  }
  return std::uint32_t(b << 16 | a);
}

inline std::uint32_t be32(const std::uint8_t* p) {
  return std::uint32_t(p[0]) << 24 | std::uint32_t(p[1]) << 16 | std::uint32_t(p[2]) << 8 | p[3];
}

class BitReader {
 public:
  BitReader(const std::vector<std::uint8_t>& d, std::size_t start) : d_(d), pos_(start) {}
  std::uint32_t bit() {
    if (pos_ >= d_.size()) throw std::runtime_error("inflate: out of data");
    const std::uint32_t b = (d_[pos_] >> bit_) & 1u;
    if (++bit_ == 8) bit_ = 0, ++pos_;
    return b;
  }
  std::uint32_t bits(int n) {  // least significant bit first
    std::uint32_t v = 0;
    for (int i = 0; i < n; ++i) v |= bit() << i;
    return v;
  }
  void align() {
    if (bit_) bit_ = 0, ++pos_;
  }
  std::size_t pos() const { return pos_; }
  std::uint8_t byte() {
    if (pos_ >= d_.size()) throw std::runtime_error("inflate: out of data");
    return d_[pos_++];
  }

 private:
  const std::vector<std::uint8_t>& d_;
  std::size_t pos_;
  int bit_ = 0;
};

struct Inflated {
  std::vector<std::uint8_t> data;
  std::vector<int> block_types;
  std::size_t end = 0;  // byte offset just after the last block
};

inline Inflated inflate(const std::vector<std::uint8_t>& z, std::size_t start) {
  // Length codes 257..285 and distance codes 0..29, built from the rules of RFC 1951 3.2.5.
  int lbase[29], lextra[29], dbase[30], dextra[30];
  for (int i = 0; i < 29; ++i) {
    lextra[i] = i < 8 ? 0 : (i - 4) / 4;
    lbase[i] = i == 0 ? 3 : lbase[i - 1] + (1 << lextra[i - 1]);
  }
  lbase[28] = 258, lextra[28] = 0;
  for (int i = 0; i < 30; ++i) {
    dextra[i] = i < 4 ? 0 : (i - 2) / 2;
    dbase[i] = i == 0 ? 1 : dbase[i - 1] + (1 << dextra[i - 1]);
  }
  Inflated out;
  BitReader br(z, start);
  for (bool last = false; !last;) {
    last = br.bit();
    const int type = int(br.bits(2));
    out.block_types.push_back(type);
    if (type == 0) {
      br.align();
      const unsigned len = br.byte() | unsigned(br.byte()) << 8;
      const unsigned nlen = br.byte() | unsigned(br.byte()) << 8;
      if ((len ^ 0xFFFFu) != nlen) throw std::runtime_error("inflate: stored LEN/NLEN mismatch");
      for (unsigned i = 0; i < len; ++i) out.data.push_back(br.byte());
    } else if (type == 1) {
      for (;;) {
        std::uint32_t code = 0;
        int sym = -1;
        for (int len = 1; len <= 9 && sym < 0; ++len) {
          code = code << 1 | br.bit();
          if (len == 7 && code <= 0x17) sym = 256 + int(code);
          else if (len == 8 && code >= 0x30 && code <= 0xBF) sym = int(code) - 0x30;
          else if (len == 8 && code >= 0xC0 && code <= 0xC7) sym = 280 + int(code) - 0xC0;
          else if (len == 9 && code >= 0x190) sym = 144 + int(code) - 0x190;
        }
        if (sym < 0 || sym > 285) throw std::runtime_error("inflate: bad literal/length code");
        if (sym < 256) {
          out.data.push_back(std::uint8_t(sym));
          continue;
        }
        if (sym == 256) break;
        const int li = sym - 257;
        const int length = lbase[li] + int(br.bits(lextra[li]));
        std::uint32_t dc = 0;
        for (int k = 0; k < 5; ++k) dc = dc << 1 | br.bit();  // fixed 5-bit code, most significant first
        if (dc > 29) throw std::runtime_error("inflate: bad distance code");
        const std::size_t dist = std::size_t(dbase[dc]) + br.bits(dextra[dc]);
        if (dist > out.data.size()) throw std::runtime_error("inflate: distance before start");
        for (int k = 0; k < length; ++k) out.data.push_back(out.data[out.data.size() - dist]);
      }
    } else {
      throw std::runtime_error("inflate: block type " + std::to_string(type) + " not supported by the test reader");
    }
  }
  br.align();
  out.end = br.pos();
  return out;
}

struct Chunk {
  std::string type;
  std::vector<std::uint8_t> data;
  std::uint32_t crc_stored = 0, crc_computed = 0;
};

struct Png {
  std::vector<Chunk> chunks;
  int width = 0, height = 0, bit_depth = 0, colour_type = 0, compression = 0, filter = 0, interlace = 0;
  std::vector<std::uint8_t> zlib;      // concatenated IDAT data
  Inflated raw;                        // filtered scanlines
  std::uint32_t adler_stored = 0, adler_computed = 0;
  std::vector<std::uint8_t> rgb;       // unfiltered pixels
  std::uint8_t at(int x, int y, int c) const { return rgb[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3 + std::size_t(c)]; }
};

inline Png decode(const std::vector<std::uint8_t>& f) {
  static const std::uint8_t sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (f.size() < 8 || !std::equal(sig, sig + 8, f.begin())) throw std::runtime_error("bad PNG signature");
  Png p;
  std::size_t pos = 8;
  while (pos < f.size()) {
    if (pos + 12 > f.size()) throw std::runtime_error("truncated chunk header");
    const std::uint32_t len = be32(&f[pos]);
    if (pos + 12 + len > f.size()) throw std::runtime_error("truncated chunk");
    Chunk c;
    c.type.assign(reinterpret_cast<const char*>(&f[pos + 4]), 4);
    c.data.assign(f.begin() + std::ptrdiff_t(pos + 8), f.begin() + std::ptrdiff_t(pos + 8 + len));
    c.crc_stored = be32(&f[pos + 8 + len]);
    c.crc_computed = crc32_bitwise(&f[pos + 4], len + 4);
    p.chunks.push_back(std::move(c));
    pos += 12 + len;
  }
  if (p.chunks.empty() || p.chunks.front().type != "IHDR" || p.chunks.front().data.size() != 13)
    throw std::runtime_error("first chunk is not a 13-byte IHDR");
  const auto& h = p.chunks.front().data;
  p.width = int(be32(&h[0])), p.height = int(be32(&h[4]));
  p.bit_depth = h[8], p.colour_type = h[9], p.compression = h[10], p.filter = h[11], p.interlace = h[12];
  for (const auto& c : p.chunks)
    if (c.type == "IDAT") p.zlib.insert(p.zlib.end(), c.data.begin(), c.data.end());
  if (p.zlib.size() < 6) throw std::runtime_error("no image data");
  if ((p.zlib[0] & 0x0F) != 8 || (p.zlib[0] * 256u + p.zlib[1]) % 31 != 0 || (p.zlib[1] & 0x20))
    throw std::runtime_error("bad zlib header");
  p.raw = inflate(p.zlib, 2);
  if (p.raw.end + 4 > p.zlib.size()) throw std::runtime_error("missing Adler-32");
  p.adler_stored = be32(&p.zlib[p.raw.end]);
  p.adler_computed = adler32_plain(p.raw.data.data(), p.raw.data.size());
  if (p.bit_depth != 8 || p.colour_type != 2) throw std::runtime_error("test reader handles RGB8 only");
  const std::size_t stride = std::size_t(p.width) * 3 + 1;
  if (p.raw.data.size() != stride * std::size_t(p.height)) throw std::runtime_error("wrong amount of image data");
  for (int y = 0; y < p.height; ++y) {
    if (p.raw.data[stride * std::size_t(y)] != 0) throw std::runtime_error("test reader handles filter 0 only");
    p.rgb.insert(p.rgb.end(), p.raw.data.begin() + std::ptrdiff_t(stride * std::size_t(y) + 1),
                 p.raw.data.begin() + std::ptrdiff_t(stride * std::size_t(y + 1)));
  }
  return p;
}

inline Png decode_file(const std::string& path) { return decode(read_bytes(path)); }

}  // namespace png_test
