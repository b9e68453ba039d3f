#include "knitforge/io/png_image.h"

#include <png.h>

#include <cstring>
#include <ostream>

#include <fmt/core.h>

#include "knitforge/io/io_detail.h"
#include "knitforge/util/atomic_file.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

// libpng prints through its default handlers; the library must not print,
// so errors only jump back (the caller turns them into IOError) and warnings
// are dropped.
[[noreturn]] void on_error(png_structp png, png_const_charp) { png_longjmp(png, 1); }
void on_warning(png_structp, png_const_charp) {}

void append(png_structp png, png_bytep data, png_size_t n) {
  static_cast<std::string*>(png_get_io_ptr(png))->append(reinterpret_cast<const char*>(data), n);
}
void flush(png_structp) {}

// Encodes 8-bit RGB rows; false when libpng reports an error. Everything
// with a destructor lives outside this function (setjmp).
bool encode(const std::vector<png_bytep>& rows, int w, int h, std::string* out) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, on_error, on_warning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_set_write_fn(png, out, append, flush);
  png_set_IHDR(png, info, static_cast<png_uint_32>(w), static_cast<png_uint_32>(h), 8, PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  // No per-row filter: our pictures are flat colour areas that deflate
  // compresses well as they are, and libpng's default adaptive filtering
  // (trying all five filters on every row) took 60 % of the time of a
  // 1.7-megapixel knitting map (79 ms -> 31 ms; the file grows 16 -> 32 kB).
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_NONE);
  png_write_info(png, info);
  png_write_image(png, const_cast<png_bytepp>(rows.data()));
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

struct Source {
  const std::string* data;
  size_t pos;
};
void read_fn(png_structp png, png_bytep out, png_size_t n) {
  auto* s = static_cast<Source*>(png_get_io_ptr(png));
  if (s->pos + n > s->data->size()) png_error(png, "truncated file");
  std::memcpy(out, s->data->data() + s->pos, n);
  s->pos += n;
}

// Decodes into `pixels` (resized by the caller after the header is read, so
// everything with a destructor is owned outside; setjmp).
bool decode(Source* src, int* w, int* h, std::vector<uint8_t>* pixels, std::vector<png_bytep>* rows) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, on_error, on_warning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  png_set_read_fn(png, src, read_fn);
  png_read_info(png, info);
  const png_uint_32 pw = png_get_image_width(png, info), ph = png_get_image_height(png, info);
  if (pw == 0 || ph == 0 || pw > 65535 || ph > 65535) png_error(png, "unsupported size");
  png_set_expand(png);
  png_set_strip_16(png);
  png_set_strip_alpha(png);
  png_set_gray_to_rgb(png);
  png_read_update_info(png, info);
  if (png_get_rowbytes(png, info) != 3 * static_cast<size_t>(pw)) png_error(png, "unexpected row size");
  *w = static_cast<int>(pw);
  *h = static_cast<int>(ph);
  pixels->resize(3 * static_cast<size_t>(pw) * ph);
  rows->resize(ph);
  for (png_uint_32 y = 0; y < ph; ++y) (*rows)[y] = pixels->data() + 3 * static_cast<size_t>(pw) * y;
  png_read_image(png, rows->data());
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

}  // namespace

void write_png(const std::string& path, const RgbImage& image) {
  if (image.width < 1 || image.height < 1) {
    throw InvalidInput(fmt::format("{}: image size {}x{} must be positive", path, image.width, image.height));
  }
  const size_t need = 3 * static_cast<size_t>(image.width) * static_cast<size_t>(image.height);
  if (image.pixels.size() != need) {
    throw InvalidInput(fmt::format("{}: {} pixel bytes for a {}x{} RGB image (need {})", path,
                                   image.pixels.size(), image.width, image.height, need));
  }
  std::vector<png_bytep> rows(static_cast<size_t>(image.height));
  for (int y = 0; y < image.height; ++y) {
    rows[static_cast<size_t>(y)] = const_cast<png_bytep>(
        image.pixels.data() + 3 * static_cast<size_t>(image.width) * static_cast<size_t>(y));
  }
  std::string encoded;
  if (!encode(rows, image.width, image.height, &encoded))
    throw IOError(fmt::format("{}: PNG encoding failed", path));
  write_file_atomically(
      path, [&](std::ostream& o) { o.write(encoded.data(), static_cast<std::streamsize>(encoded.size())); },
      true);
}

RgbImage read_png(const std::string& path) {
  const std::string data = io_detail::load_file(path);
  if (data.size() < 8 || png_sig_cmp(reinterpret_cast<png_const_bytep>(data.data()), 0, 8) != 0) {
    throw IOError(fmt::format("{}: not a PNG file (bad signature)", path));
  }
  Source src{&data, 0};
  RgbImage img;
  std::vector<png_bytep> rows;
  if (!decode(&src, &img.width, &img.height, &img.pixels, &rows)) {
    throw IOError(fmt::format("{}: malformed or truncated PNG", path));
  }
  return img;
}

}  // namespace knitforge
