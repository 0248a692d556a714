// An 8-bit RGB picture in memory and its PNG file. Rows run from the top of the picture down, as in
// PNG. The PNG writer is deterministic (no time stamp, fixed compression), so the same pixels give
// the same bytes; the reader takes any 8-bit PNG (grey, palette, RGB, with or without alpha, which
// is laid over black) so that tests can read screenshots back.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace fastcorot {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  // width × height × 3, row after row from the top left

  Image() = default;
  Image(int width, int height)
      : width(width), height(height), rgb(static_cast<std::size_t>(width) * height * 3, 0) {}

  std::array<std::uint8_t, 3> pixel(int x, int y) const {
    const std::size_t at = (static_cast<std::size_t>(y) * width + x) * 3;
    return {rgb[at], rgb[at + 1], rgb[at + 2]};
  }
};

// A picture size given as "WIDTHxHEIGHT" (e.g. 800x450), each within [16, 8192]; throws
// fastcorot::Error naming `option` and the text otherwise.
struct ImageSize {
  int width = 800;
  int height = 450;
};
ImageSize parse_image_size(const std::string& text, const std::string& option = "--size");

// Throws fastcorot::Error naming the file when it cannot be written.
void write_png(const std::filesystem::path& path, const Image& image);

// Throws fastcorot::Error naming the file when it is missing, not a PNG, 16-bit, or corrupt.
Image read_png(const std::filesystem::path& path);

}  // namespace fastcorot
