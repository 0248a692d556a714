#include "fastcorot/render/image.h"

#include "fastcorot/core/error.h"
#include "fastcorot/io/atomic_file.h"

#include <png.h>

#include <cstdio>
#include <cstring>
#include <memory>

namespace fastcorot {

namespace {

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

// libpng reports errors through a callback; turning them into an exception thrown across C frames
// is not safe, so the callback records the message and longjmps back as libpng requires.
void record_error(png_structp png, png_const_charp message) {
  auto* text = static_cast<std::string*>(png_get_error_ptr(png));
  *text = message;
  png_longjmp(png, 1);
}
void ignore_warning(png_structp, png_const_charp) {}

}  // namespace

ImageSize parse_image_size(const std::string& text, const std::string& option) {
  ImageSize size;
  char x = 0;
  char rest = 0;
  const int read = std::sscanf(text.c_str(), "%d%c%d%c", &size.width, &x, &size.height, &rest);
  if (read != 3 || x != 'x' || size.width < 16 || size.height < 16 || size.width > 8192 ||
      size.height > 8192) {
    throw make_error(option, " \"", text,
                     "\": expected WIDTHxHEIGHT in pixels (e.g. 800x450), each in [16, 8192]");
  }
  return size;
}

void write_png(const std::filesystem::path& path, const Image& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgb.size() != static_cast<std::size_t>(image.width) * image.height * 3) {
    throw make_error(path.string(), ": cannot write an image of ", image.width, "x", image.height,
                     " with ", image.rgb.size(), " bytes");
  }
  write_file_atomically(path, [&](const std::filesystem::path& temporary) {
    File file(std::fopen(temporary.c_str(), "wb"));
    if (!file) throw make_error(path.string(), ": cannot write: ", std::strerror(errno));
    std::string error;
    png_structp png =
        png_create_write_struct(PNG_LIBPNG_VER_STRING, &error, record_error, ignore_warning);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!info) {
      png_destroy_write_struct(&png, nullptr);
      throw make_error(path.string(), ": out of memory for the PNG writer");
    }
    if (setjmp(png_jmpbuf(png))) {
      png_destroy_write_struct(&png, &info);
      throw make_error(path.string(), ": cannot write the PNG: ", error);
    }
    png_init_io(png, file.get());
    png_set_IHDR(png, info, static_cast<png_uint_32>(image.width),
                 static_cast<png_uint_32>(image.height), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_compression_level(png, 6);
    png_write_info(png, info);
    for (int y = 0; y < image.height; ++y) {
      png_write_row(png, image.rgb.data() + static_cast<std::size_t>(y) * image.width * 3);
    }
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    if (std::fflush(file.get()) != 0 || std::ferror(file.get())) {
      throw make_error(path.string(), ": cannot write: ", std::strerror(errno));
    }
  });
}

Image read_png(const std::filesystem::path& path) {
  File file(std::fopen(path.c_str(), "rb"));
  if (!file) throw make_error(path.string(), ": cannot open: ", std::strerror(errno));
  png_byte signature[8] = {};
  if (std::fread(signature, 1, 8, file.get()) != 8 || png_sig_cmp(signature, 0, 8) != 0) {
    throw make_error(path.string(), ": not a PNG file");
  }
  std::string error;
  png_structp png =
      png_create_read_struct(PNG_LIBPNG_VER_STRING, &error, record_error, ignore_warning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    throw make_error(path.string(), ": out of memory for the PNG reader");
  }
  Image image;
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    throw make_error(path.string(), ": corrupt PNG: ", error);
  }
  png_init_io(png, file.get());
  png_set_sig_bytes(png, 8);
  png_read_info(png, info);
  if (png_get_bit_depth(png, info) == 16) {
    png_destroy_read_struct(&png, &info, nullptr);
    throw make_error(path.string(), ": 16-bit PNG files are not supported");
  }
  // Everything becomes 8-bit RGB: palettes expanded, grey copied to three channels, alpha dropped
  // after compositing over black.
  png_set_expand(png);
  png_set_gray_to_rgb(png);
  png_color_16 black{};
  png_set_background(png, &black, PNG_BACKGROUND_GAMMA_SCREEN, 0, 1.0);
  png_read_update_info(png, info);
  image = Image(static_cast<int>(png_get_image_width(png, info)),
                static_cast<int>(png_get_image_height(png, info)));
  if (png_get_rowbytes(png, info) != static_cast<std::size_t>(image.width) * 3) {
    png_destroy_read_struct(&png, &info, nullptr);
    throw make_error(path.string(), ": unexpected PNG layout");
  }
  for (int y = 0; y < image.height; ++y)
    png_read_row(png, image.rgb.data() + static_cast<std::size_t>(y) * image.width * 3, nullptr);
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return image;
}

}  // namespace fastcorot
