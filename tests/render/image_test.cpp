// PNG files: a round trip keeps every pixel, the same image gives the same bytes, and bad sizes,
// paths and files are errors that name them.
#include "fastcorot/render/image.h"

#include "fastcorot/core/error.h"
#include "render/render_scenes.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

namespace fastcorot {
namespace {

std::filesystem::path temp(const std::string& name) {
  return testing::unique_temp_path(name);
}

std::string bytes_of(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

Image pattern() {
  Image image(37, 23);  // odd sizes: no row padding assumptions
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const std::size_t at = (static_cast<std::size_t>(y) * image.width + x) * 3;
      image.rgb[at] = static_cast<std::uint8_t>(7 * x);
      image.rgb[at + 1] = static_cast<std::uint8_t>(11 * y);
      image.rgb[at + 2] = static_cast<std::uint8_t>(x * y);
    }
  }
  return image;
}

TEST(Image, PngRoundTripIsExactAndDeterministic) {
  const Image image = pattern();
  const auto a = temp("fastcorot_image_a.png"), b = temp("fastcorot_image_b.png");
  write_png(a, image);
  write_png(b, image);
  const Image read = read_png(a);
  EXPECT_EQ(read.width, image.width);
  EXPECT_EQ(read.height, image.height);
  EXPECT_EQ(read.rgb, image.rgb);
  EXPECT_EQ(read.pixel(5, 3), (std::array<std::uint8_t, 3>{35, 33, 15}));
  EXPECT_EQ(bytes_of(a), bytes_of(b));
  std::filesystem::remove(a);
  std::filesystem::remove(b);
}

TEST(Image, ParsesSizes) {
  const ImageSize size = parse_image_size("800x450");
  EXPECT_EQ(size.width, 800);
  EXPECT_EQ(size.height, 450);
  for (const std::string bad :
       {"800", "800x", "x450", "0x450", "800x8", "800x450x3", "800 450", "99999x10", "-800x450"}) {
    try {
      parse_image_size(bad);
      ADD_FAILURE() << "accepted " << bad;
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find("--size \"" + bad + "\""), std::string::npos)
          << error.what();
    }
  }
}

TEST(Image, FileErrorsNameTheFile) {
  const Image image = pattern();
  try {
    write_png("/nonexistent-folder/picture.png", image);
    FAIL() << "wrote into a missing folder";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("/nonexistent-folder/picture.png"), std::string::npos);
  }
  EXPECT_THROW(write_png(temp("fastcorot_empty.png"), Image()), Error);
  EXPECT_THROW(read_png(temp("fastcorot_missing.png")), Error);
  const auto text = temp("fastcorot_not_a.png");
  std::ofstream(text) << "not a picture";
  EXPECT_THROW(read_png(text), Error);
  std::filesystem::remove(text);
  // A PNG cut short.
  const auto cut = temp("fastcorot_cut.png");
  write_png(cut, image);
  std::filesystem::resize_file(cut, 60);
  EXPECT_THROW(read_png(cut), Error);
  std::filesystem::remove(cut);
}

}  // namespace
}  // namespace fastcorot
