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

// Encodes rows of the given bit depth and colour type; false when libpng
// reports an error. Everything with a destructor lives outside this function
// (setjmp).
bool encode(const std::vector<png_bytep>& rows, int w, int h, int bit_depth, int colour_type, std::string* out) {
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
  png_set_IHDR(png, info, static_cast<png_uint_32>(w), static_cast<png_uint_32>(h), bit_depth, colour_type,
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

// What decode() found.
enum class DecodeStatus { Ok, OtherKind, Failed };

// The two ways of decoding: any PNG converted to 8-bit RGB, or a 16-bit
// greyscale PNG as stored (big-endian bytes; another kind is OtherKind).
enum class DecodeAs { Rgb8, Gray16 };

// Decodes into `pixels` (resized by the caller after the header is read, so
// everything with a destructor is owned outside; setjmp). `bit_depth` and
// `colour_type` receive the file's.
DecodeStatus decode(Source* src, DecodeAs as, int* w, int* h, int* bit_depth, int* colour_type,
                    std::vector<uint8_t>* pixels, std::vector<png_bytep>* rows) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, on_error, on_warning);
  if (!png) return DecodeStatus::Failed;
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    return DecodeStatus::Failed;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    return DecodeStatus::Failed;
  }
  png_set_read_fn(png, src, read_fn);
  png_read_info(png, info);
  const png_uint_32 pw = png_get_image_width(png, info), ph = png_get_image_height(png, info);
  if (pw == 0 || ph == 0 || pw > 65535 || ph > 65535) png_error(png, "unsupported size");
  *bit_depth = png_get_bit_depth(png, info);
  *colour_type = png_get_color_type(png, info);
  size_t bytes_per_pixel = 3;
  if (as == DecodeAs::Gray16) {
    if (*bit_depth != 16 || *colour_type != PNG_COLOR_TYPE_GRAY) {
      png_destroy_read_struct(&png, &info, nullptr);
      return DecodeStatus::OtherKind;
    }
    bytes_per_pixel = 2;
  } else {
    png_set_expand(png);
    png_set_strip_16(png);
    png_set_strip_alpha(png);
    png_set_gray_to_rgb(png);
  }
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  if (png_get_rowbytes(png, info) != bytes_per_pixel * pw) png_error(png, "unexpected row size");
  *w = static_cast<int>(pw);
  *h = static_cast<int>(ph);
  pixels->resize(bytes_per_pixel * pw * ph);
  rows->resize(ph);
  for (png_uint_32 y = 0; y < ph; ++y) (*rows)[y] = pixels->data() + bytes_per_pixel * pw * y;
  png_read_image(png, rows->data());
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return DecodeStatus::Ok;
}

std::string png_kind(int bit_depth, int colour_type) {
  const char* kind = colour_type == PNG_COLOR_TYPE_GRAY         ? "greyscale"
                     : colour_type == PNG_COLOR_TYPE_GRAY_ALPHA ? "greyscale+alpha"
                     : colour_type == PNG_COLOR_TYPE_PALETTE    ? "palette"
                     : colour_type == PNG_COLOR_TYPE_RGB        ? "RGB"
                     : colour_type == PNG_COLOR_TYPE_RGB_ALPHA  ? "RGBA"
                                                                : "unknown colour type";
  return fmt::format("{}-bit {}", bit_depth, kind);
}

void write_encoded(const std::string& path, const std::string& encoded) {
  write_file_atomically(
      path, [&](std::ostream& o) { o.write(encoded.data(), static_cast<std::streamsize>(encoded.size())); },
      true);
}

std::string load_png_file(const std::string& path) {
  std::string data = io_detail::load_file(path);
  if (data.size() < 8 || png_sig_cmp(reinterpret_cast<png_const_bytep>(data.data()), 0, 8) != 0) {
    throw IOError(fmt::format("{}: not a PNG file (bad signature)", path));
  }
  return data;
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
  if (!encode(rows, image.width, image.height, 8, PNG_COLOR_TYPE_RGB, &encoded))
    throw IOError(fmt::format("{}: PNG encoding failed", path));
  write_encoded(path, encoded);
}

RgbImage read_png(const std::string& path) {
  const std::string data = load_png_file(path);
  Source src{&data, 0};
  RgbImage img;
  int bit_depth = 0, colour_type = 0;
  std::vector<png_bytep> rows;
  if (decode(&src, DecodeAs::Rgb8, &img.width, &img.height, &bit_depth, &colour_type, &img.pixels, &rows) !=
      DecodeStatus::Ok) {
    throw IOError(fmt::format("{}: malformed or truncated PNG", path));
  }
  return img;
}

void write_png_gray16(const std::string& path, const Gray16Image& image) {
  if (image.width < 1 || image.height < 1 || image.width > 65535 || image.height > 65535) {
    throw InvalidInput(fmt::format("{}: image size {}x{} must be 1..65535 per side", path, image.width, image.height));
  }
  const size_t w = static_cast<size_t>(image.width), n = w * static_cast<size_t>(image.height);
  if (image.pixels.size() != n) {
    throw InvalidInput(fmt::format("{}: {} pixel values for a {}x{} image (need {})", path, image.pixels.size(),
                                   image.width, image.height, n));
  }
  // PNG stores 16-bit samples big-endian.
  std::vector<uint8_t> bytes(2 * n);
  for (size_t i = 0; i < n; ++i) {
    bytes[2 * i] = static_cast<uint8_t>(image.pixels[i] >> 8);
    bytes[2 * i + 1] = static_cast<uint8_t>(image.pixels[i] & 0xff);
  }
  std::vector<png_bytep> rows(static_cast<size_t>(image.height));
  for (size_t y = 0; y < rows.size(); ++y) rows[y] = bytes.data() + 2 * w * y;
  std::string encoded;
  if (!encode(rows, image.width, image.height, 16, PNG_COLOR_TYPE_GRAY, &encoded))
    throw IOError(fmt::format("{}: PNG encoding failed", path));
  write_encoded(path, encoded);
}

Gray16Image read_png_gray16(const std::string& path) {
  const std::string data = load_png_file(path);
  Source src{&data, 0};
  Gray16Image img;
  int bit_depth = 0, colour_type = 0;
  std::vector<uint8_t> bytes;
  std::vector<png_bytep> rows;
  const DecodeStatus status =
      decode(&src, DecodeAs::Gray16, &img.width, &img.height, &bit_depth, &colour_type, &bytes, &rows);
  if (status == DecodeStatus::OtherKind) {
    throw IOError(fmt::format("{}: {} PNG; a depth image is a 16-bit greyscale PNG (one channel, depth units)", path,
                              png_kind(bit_depth, colour_type)));
  }
  if (status == DecodeStatus::Failed) throw IOError(fmt::format("{}: malformed or truncated PNG", path));
  img.pixels.resize(bytes.size() / 2);
  for (size_t i = 0; i < img.pixels.size(); ++i)
    img.pixels[i] = static_cast<uint16_t>((static_cast<unsigned>(bytes[2 * i]) << 8) | bytes[2 * i + 1]);
  return img;
}

}  // namespace knitforge
