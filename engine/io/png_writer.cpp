// PNG encoding with libpng into memory (its error path is setjmp/longjmp, kept inside this
// function), then one atomic write.
#include "io/png_writer.h"

#include <png.h>

#include <csetjmp>
#include <string>
#include <vector>

#include "io/atomic_file.h"

namespace scansurf {
namespace {

void appendToVector(png_structp png, png_bytep data, png_size_t size) {
  auto* out = static_cast<std::vector<std::uint8_t>*>(png_get_io_ptr(png));
  out->insert(out->end(), data, data + size);
}

// Encodes without any C++ object whose destructor a longjmp would skip.
bool encode(std::uint32_t width, std::uint32_t height, const std::uint8_t* rgba, std::vector<std::uint8_t>* out,
            std::vector<png_bytep>* rows) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, info ? &info : nullptr);
    return false;
  }
  png_set_write_fn(png, out, appendToVector, nullptr);
  png_set_IHDR(png, info, width, height, 8, PNG_COLOR_TYPE_RGBA, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  for (std::uint32_t y = 0; y < height; ++y) (*rows)[y] = const_cast<png_bytep>(rgba + std::size_t{4} * width * y);
  png_set_rows(png, info, rows->data());
  png_write_png(png, info, PNG_TRANSFORM_IDENTITY, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

Result<void> writePng(const std::filesystem::path& path, std::uint32_t width, std::uint32_t height,
                      std::span<const std::uint8_t> rgba) {
  if (width == 0 || height == 0 || rgba.size() != std::size_t{4} * width * height)
    return makeError(Errc::InvalidArgument, "cannot write '" + path.string() + "': image size does not match its pixels");
  std::vector<std::uint8_t> encoded;
  std::vector<png_bytep> rows(height);
  if (!encode(width, height, rgba.data(), &encoded, &rows))
    return makeError(Errc::Internal, "cannot write '" + path.string() + "': PNG encoding failed");
  return writeFileAtomically(path, encoded.data(), encoded.size());
}

}  // namespace scansurf
