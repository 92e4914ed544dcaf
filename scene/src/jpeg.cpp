// JPEG through libjpeg-turbo: robust on corrupt input (the stb decoder of Debian 12 aborts on
// bad Huffman data, found by fuzz_net_video) and SIMD-fast for video frames.
// libjpeg reports fatal errors through a callback that must not return: it longjmps back to
// the setjmp in encodeWith/decodeWith, which therefore hold no objects with destructors.
#include "vt/scene/jpeg.hpp"

#include <csetjmp>
#include <cstdio>
#include <cstdlib>
// jpeglib.h needs size_t and FILE declared first.
#include <jpeglib.h>

#include "vt/core/error.hpp"

namespace vt {
namespace {

constexpr int kMaxScans = 100;  // a progressive frame needs ~10; thousands of tiny scans are a CPU trap

struct JpegError {
  jpeg_error_mgr manager;  // first: libjpeg hands back a pointer to it
  std::jmp_buf jump;
  int warnings = 0;
  char message[JMSG_LENGTH_MAX] = {};
};

JpegError& errorOf(j_common_ptr cinfo) { return *reinterpret_cast<JpegError*>(cinfo->err); }

[[noreturn]] void onError(j_common_ptr cinfo) {
  (*cinfo->err->format_message)(cinfo, errorOf(cinfo).message);
  std::longjmp(errorOf(cinfo).jump, 1);
}

// Warnings (level -1) mean corrupt data that libjpeg would paper over: keep the first one.
void onMessage(j_common_ptr cinfo, int level) {
  if (level >= 0) return;
  if (errorOf(cinfo).warnings++ == 0) (*cinfo->err->format_message)(cinfo, errorOf(cinfo).message);
}

void onProgress(j_common_ptr cinfo) {
  auto* decompress = reinterpret_cast<j_decompress_ptr>(cinfo);
  if (decompress->input_scan_number > kMaxScans) {
    std::snprintf(errorOf(cinfo).message, JMSG_LENGTH_MAX, "more than %d scans", kMaxScans);
    std::longjmp(errorOf(cinfo).jump, 1);
  }
}

void hookErrors(JpegError& error) {
  jpeg_std_error(&error.manager);
  error.manager.error_exit = onError;
  error.manager.emit_message = onMessage;
}

struct Compressor {
  jpeg_compress_struct cinfo{};
  JpegError error;
  bool created = false;
  unsigned char* buffer = nullptr;
  unsigned long size = 0;
  ~Compressor() {
    if (created) jpeg_destroy_compress(&cinfo);
    std::free(buffer);  // jpeg_mem_dest allocates with malloc
  }
};

struct Decompressor {
  jpeg_decompress_struct cinfo{};
  JpegError error;
  jpeg_progress_mgr progress{};
  bool created = false;
  ~Decompressor() {
    if (created) jpeg_destroy_decompress(&cinfo);
  }
};

bool encodeWith(Compressor& c, const Image8& image, int quality) {
  hookErrors(c.error);
  c.cinfo.err = &c.error.manager;
  if (setjmp(c.error.jump)) return false;
  jpeg_create_compress(&c.cinfo);
  c.created = true;
  jpeg_mem_dest(&c.cinfo, &c.buffer, &c.size);
  c.cinfo.image_width = JDIMENSION(image.width);
  c.cinfo.image_height = JDIMENSION(image.height);
  c.cinfo.input_components = image.channels;
  c.cinfo.in_color_space = image.channels == 1 ? JCS_GRAYSCALE : image.channels == 3 ? JCS_EXT_RGB : JCS_EXT_RGBA;
  jpeg_set_defaults(&c.cinfo);
  jpeg_set_quality(&c.cinfo, quality, TRUE);
  jpeg_start_compress(&c.cinfo, TRUE);
  const std::size_t stride = std::size_t(image.width) * image.channels;
  while (c.cinfo.next_scanline < c.cinfo.image_height) {
    // libjpeg's row type is non-const; it only reads the rows.
    JSAMPROW row = const_cast<JSAMPROW>(image.pixels.data() + c.cinfo.next_scanline * stride);
    jpeg_write_scanlines(&c.cinfo, &row, 1);
  }
  jpeg_finish_compress(&c.cinfo);
  return true;
}

bool decodeWith(Decompressor& d, std::span<const std::uint8_t> bytes, Image8& out) {
  hookErrors(d.error);
  d.cinfo.err = &d.error.manager;
  if (setjmp(d.error.jump)) return false;
  jpeg_create_decompress(&d.cinfo);
  d.created = true;
  d.progress.progress_monitor = onProgress;
  d.cinfo.progress = &d.progress;
  jpeg_mem_src(&d.cinfo, bytes.data(), static_cast<unsigned long>(bytes.size()));
  jpeg_read_header(&d.cinfo, TRUE);
  const long long w = d.cinfo.image_width, h = d.cinfo.image_height;
  if (w < 1 || h < 1 || w * h > kMaxJpegPixels) {
    std::snprintf(d.error.message, JMSG_LENGTH_MAX, "JPEG size %lldx%lld outside 1..%lld pixels", w, h, kMaxJpegPixels);
    return false;
  }
  d.cinfo.out_color_space = JCS_EXT_RGBA;
  jpeg_start_decompress(&d.cinfo);
  out.width = int(d.cinfo.output_width);
  out.height = int(d.cinfo.output_height);
  out.channels = 4;
  out.pixels.resize(std::size_t(out.width) * out.height * 4);
  while (d.cinfo.output_scanline < d.cinfo.output_height && d.error.warnings == 0) {
    JSAMPROW row = out.pixels.data() + std::size_t(d.cinfo.output_scanline) * out.width * 4;
    jpeg_read_scanlines(&d.cinfo, &row, 1);
  }
  if (d.error.warnings == 0) jpeg_finish_decompress(&d.cinfo);
  return d.error.warnings == 0;
}

}  // namespace

std::vector<std::uint8_t> encodeJpeg(const Image8& image, int quality) {
  if (image.channels != 1 && image.channels != 3 && image.channels != 4)
    fail("encodeJpeg: ", image.channels, " channels (expected 1, 3 or 4)");
  if (image.width <= 0 || image.height <= 0 || image.pixels.size() != std::size_t(image.width) * image.height * image.channels)
    fail("encodeJpeg: empty or inconsistent image (", image.width, "x", image.height, ")");
  if (quality < 1 || quality > 100) fail("encodeJpeg: quality ", quality, " not in 1..100");
  Compressor compressor;
  if (!encodeWith(compressor, image, quality)) fail("encodeJpeg: libjpeg failed (", compressor.error.message, ")");
  return {compressor.buffer, compressor.buffer + compressor.size};
}

Image8 decodeJpeg(std::span<const std::uint8_t> bytes, const std::string& source) {
  if (bytes.size() > kMaxJpegBytes) fail(source, ": JPEG of ", bytes.size(), " bytes exceeds the ", kMaxJpegBytes, "-byte limit");
  if (bytes.size() < 4 || bytes[0] != 0xFF || bytes[1] != 0xD8 || bytes[2] != 0xFF)
    fail(source, ": not a JPEG (no start-of-image marker)");
  Decompressor decompressor;
  Image8 image;
  if (!decodeWith(decompressor, bytes, image)) fail(source, ": cannot decode JPEG (", decompressor.error.message, ")");
  return image;
}

}  // namespace vt
