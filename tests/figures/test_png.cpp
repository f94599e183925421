// PNG encoder: checksums against published values, file layout, and exact pixel round trips
// through the independent reader in png_reader.hpp (stored and fixed-Huffman streams).
#include <catch2/catch.hpp>

#include <cstring>
#include <filesystem>
#include <random>
#include <string>

#include "furniture_fem/figures/plot.hpp"
#include "png_reader.hpp"
#include "../support/test_files.hpp"

namespace fs = std::filesystem;
using namespace furniture_fem;

using ffem_test::tmp;

namespace {
const std::uint8_t* bytes(const char* s) { return reinterpret_cast<const std::uint8_t*>(s); }

// Every pixel different, so any misplaced byte is caught.
Image gradient(int w, int h) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) img.set(x, y, RGB{std::uint8_t(x * 30 + 7), std::uint8_t(y * 50 + 3), std::uint8_t((x + y) * 10)});
  return img;
}

void require_same_pixels(const png_test::Png& p, const Image& img) {
  REQUIRE(p.width == img.w);
  REQUIRE(p.height == img.h);
  REQUIRE(p.rgb == img.rgb);
}
}  // namespace

TEST_CASE("CRC-32 and Adler-32 known answers", "[png]") {
  REQUIRE(detail::png::crc32(bytes("123456789"), 9) == 0xCBF43926u);
  REQUIRE(png_test::crc32_bitwise(bytes("123456789"), 9) == 0xCBF43926u);
  REQUIRE(detail::png::crc32(bytes(""), 0) == 0u);
  // The running form continues a checksum over split data.
  REQUIRE(detail::png::crc32(bytes("56789"), 5, detail::png::crc32(bytes("1234"), 4)) == 0xCBF43926u);
  // "IEND" with no data: the CRC every PNG ends with.
  REQUIRE(detail::png::crc32(bytes("IEND"), 4) == 0xAE426082u);

  REQUIRE(detail::png::adler32(bytes("Wikipedia"), 9) == 0x11E60398u);
  REQUIRE(png_test::adler32_plain(bytes("Wikipedia"), 9) == 0x11E60398u);
  REQUIRE(detail::png::adler32(bytes(""), 0) == 1u);
  // Long input crosses the 5552-byte blocks where the modulo is deferred.
  std::vector<std::uint8_t> big(100000, 0xFF);
  for (std::size_t i = 0; i < big.size(); i += 7) big[i] = std::uint8_t(i);
  REQUIRE(detail::png::adler32(big.data(), big.size()) == png_test::adler32_plain(big.data(), big.size()));
}

TEST_CASE("stored PNG: signature, chunks, IHDR, CRCs, stored blocks, Adler-32, pixels", "[png]") {
  const Image img = gradient(7, 5);
  const std::string path = tmp("stored_7x5.png");
  write_png(path, img, PngCompression::stored);
  const auto f = png_test::read_bytes(path);

  const std::uint8_t sig[8] = {0x89, 0x50, 0x4E, 0x47, 0x0D, 0x0A, 0x1A, 0x0A};
  REQUIRE(f.size() > 8);
  REQUIRE(std::memcmp(f.data(), sig, 8) == 0);

  const png_test::Png p = png_test::decode(f);
  REQUIRE(p.chunks.size() == 3);
  CHECK(p.chunks[0].type == "IHDR");
  CHECK(p.chunks[1].type == "IDAT");
  CHECK(p.chunks[2].type == "IEND");
  CHECK(p.chunks[2].data.empty());
  for (const auto& c : p.chunks) {
    INFO("chunk " << c.type);
    CHECK(c.crc_stored == c.crc_computed);
  }
  CHECK(p.width == 7);
  CHECK(p.height == 5);
  CHECK(p.bit_depth == 8);
  CHECK(p.colour_type == 2);
  CHECK(p.compression == 0);
  CHECK(p.filter == 0);
  CHECK(p.interlace == 0);

  // zlib: CMF/FLG check bits, then parse the stored block by hand.
  const auto& z = p.zlib;
  CHECK(z[0] == 0x78);
  CHECK((z[0] * 256 + z[1]) % 31 == 0);
  CHECK((z[2] & 0x07) == 0x01);  // BFINAL = 1, BTYPE = 00
  const unsigned len = z[3] | unsigned(z[4]) << 8, nlen = z[5] | unsigned(z[6]) << 8;
  REQUIRE(len == 5 * (1 + 7 * 3));
  CHECK(nlen == (len ^ 0xFFFFu));
  REQUIRE(z.size() == 7 + len + 4);
  for (int y = 0; y < 5; ++y) {
    const std::uint8_t* row = &z[7 + std::size_t(y) * 22];
    CHECK(row[0] == 0);  // filter type None
    for (int x = 0; x < 7; ++x)
      for (int c = 0; c < 3; ++c) CHECK(row[1 + x * 3 + c] == img.rgb[(std::size_t(y) * 7 + std::size_t(x)) * 3 + std::size_t(c)]);
  }
  const std::uint32_t adler = png_test::be32(&z[7 + len]);
  CHECK(adler == png_test::adler32_plain(&z[7], len));
  CHECK(adler == p.adler_computed);
  require_same_pixels(p, img);
}

TEST_CASE("stored PNG larger than one stored block", "[png]") {
  const Image img = gradient(200, 150);  // 90150 bytes of scanlines -> two stored blocks
  const png_test::Png p = png_test::decode(encode_png(img, PngCompression::stored));
  REQUIRE(p.raw.block_types == std::vector<int>{0, 0});
  CHECK(p.adler_stored == p.adler_computed);
  require_same_pixels(p, img);
}

TEST_CASE("fixed-Huffman PNG decodes to the same pixels and is small for flat images", "[png]") {
  SECTION("plot-like image: flat background, lines, text") {
    Image img(640, 400);
    draw_line(img, 10, 10, 600, 380, palette[0], 3, true);
    fill_rect(img, {100, 100, 300, 200}, palette[1]);
    draw_text(img, 20, 300, "Hello, furniture 0123456789", colors::black, 2);
    const auto bytes = encode_png(img);
    const png_test::Png p = png_test::decode(bytes);
    REQUIRE(p.raw.block_types == std::vector<int>{1});
    CHECK(p.adler_stored == p.adler_computed);
    for (const auto& c : p.chunks) CHECK(c.crc_stored == c.crc_computed);
    require_same_pixels(p, img);
    CHECK(bytes.size() < img.rgb.size() / 20);
  }
  SECTION("noise: literals and matches at many distances") {
    std::mt19937 rng(42);
    Image img(301, 97);
    for (auto& b : img.rgb) b = std::uint8_t(rng() % 4 == 0 ? rng() : 200);  // mostly repeats, some noise
    const png_test::Png p = png_test::decode(encode_png(img));
    CHECK(p.adler_stored == p.adler_computed);
    require_same_pixels(p, img);
  }
  SECTION("file on disk, written in several IDAT chunks when large") {
    std::mt19937 rng(7);
    Image img(400, 300);
    for (auto& b : img.rgb) b = std::uint8_t(rng());  // incompressible: > 256 KiB of IDAT
    const std::string path = tmp("noise.png");
    write_png(path, img);
    const png_test::Png p = png_test::decode_file(path);
    int idat = 0;
    for (const auto& c : p.chunks) idat += c.type == "IDAT";
    CHECK(idat >= 2);
    CHECK(p.chunks.back().type == "IEND");
    require_same_pixels(p, img);
  }
}

TEST_CASE("write_png reports the path on failure", "[png]") {
  const std::string bad = tmp("no_such_dir/sub/x.png");
  try {
    write_png(bad, Image(4, 4));
    FAIL("write_png into a missing folder did not throw");
  } catch (const OutputError& e) {
    CHECK(std::string(e.what()).find(bad) != std::string::npos);
  }
  Image broken(4, 4);
  broken.rgb.pop_back();
  CHECK_THROWS_AS(write_png(tmp("broken.png"), broken), InputError);
  CHECK_THROWS_AS(write_png(tmp("empty.png"), Image()), InputError);
}
