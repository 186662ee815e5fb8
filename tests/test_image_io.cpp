// harness/image_io: EXR (OpenEXR) and PNG (stb) files round trip exactly what was written, and
// bad files fail with one error naming the path.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "harness/image_io.h"

namespace gib {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir() {
  fs::path d = fs::temp_directory_path() / fmt::format("gib_image_io_{}", ::testing::UnitTest::GetInstance()->random_seed());
  fs::create_directories(d);
  return d;
}

FloatImage ramp(uint32_t w, uint32_t h, uint32_t c) {
  FloatImage img(w, h, c);
  for (size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = float(i) * 0.37f - 3.0f + 1e-3f * float(i % 7);
  return img;
}

void expect_error_naming(const std::string& path, const std::string& what) {
  try {
    read_image(path);
    ADD_FAILURE() << path << ": expected an error";
  } catch (const std::runtime_error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(path), std::string::npos) << m;
    EXPECT_NE(m.find(what), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << "one line: " << m;
  }
}

TEST(ImageIo, FloatExrRoundTripsEveryChannelCountBitForBit) {
  const fs::path d = temp_dir();
  for (uint32_t c = 1; c <= 4; ++c) {
    FloatImage img = ramp(7, 5, c);
    img.pixels[3] = std::numeric_limits<float>::infinity();
    img.pixels[4] = 1e-40f;  // a denormal survives
    const std::string path = (d / fmt::format("f{}.exr", c)).string();
    write_exr(path, img);
    bool half = true;
    FloatImage back = read_image(path, &half);
    EXPECT_FALSE(half);
    ASSERT_EQ(back.width, 7u);
    ASSERT_EQ(back.height, 5u);
    ASSERT_EQ(back.channels, c);
    for (size_t i = 0; i < img.pixels.size(); ++i) EXPECT_EQ(back.pixels[i], img.pixels[i]) << c << " " << i;
  }
  // No temporary file is left beside the written ones.
  for (auto& e : fs::directory_iterator(d)) EXPECT_EQ(e.path().filename().string()[0] == '.', false) << e.path();
}

TEST(ImageIo, HalfExrStoresWhatRoundToHalfGives) {
  const fs::path d = temp_dir();
  FloatImage img = ramp(4, 3, 3);
  const std::string path = (d / "h.exr").string();
  write_exr(path, img, true);
  bool half = false;
  FloatImage back = read_image(path, &half);
  EXPECT_TRUE(half);
  FloatImage expect = round_to_half(img);
  ASSERT_EQ(back.pixels.size(), expect.pixels.size());
  for (size_t i = 0; i < expect.pixels.size(); ++i) EXPECT_EQ(back.pixels[i], expect.pixels[i]) << i;
}

TEST(ImageIo, PngPreviewReadsBackAsItsBytes) {
  const fs::path d = temp_dir();
  FloatImage img(2, 1, 3);
  img.pixels = {0.0f, 1.0f, 0.5f, 2.0f, -1.0f, 0.0031308f};
  const std::string path = (d / "p.png").string();
  write_png_preview(path, img);
  Rgb8Image rgb = read_rgb8(path);
  ASSERT_EQ(rgb.width, 2u);
  ASSERT_EQ(rgb.height, 1u);
  // sRGB-encoded and clamped: 0 -> 0, 1 -> 255, 0.5 -> 188, 2 -> 255, -1 -> 0, 0.0031308 -> 10.
  EXPECT_EQ(rgb.rgb, (std::vector<uint8_t>{0, 255, 188, 255, 0, 10}));
  FloatImage f = read_image(path);
  EXPECT_EQ(f.channels, 3u);
  EXPECT_FLOAT_EQ(f.pixels[2], 188.0f / 255.0f);
}

TEST(ImageIo, BadFilesFailWithOneLineNamingThePath) {
  const fs::path d = temp_dir();
  const std::string good = (d / "good.exr").string();
  write_exr(good, ramp(16, 16, 4));
  // Truncated: the header survives, the pixels do not.
  const std::string cut = (d / "cut.exr").string();
  {
    std::ifstream in(good, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), {});
    std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  }
  expect_error_naming(cut, "corrupt or unreadable EXR");
  const std::string text = (d / "text.exr").string();
  std::ofstream(text) << "not an image";
  expect_error_naming(text, "corrupt or unreadable image");
  expect_error_naming((d / "missing.exr").string(), "no such file");
  EXPECT_THROW(read_rgb8(text), std::runtime_error);
}

}  // namespace
}  // namespace gib
