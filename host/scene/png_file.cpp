#include "scene/png_file.hpp"

#include <png.h>

#include <csetjmp>
#include <cstring>
#include <new>

namespace acetate {
namespace {

// libpng reports errors by calling error_fn, which must not return: it keeps the message and
// jumps back to the setjmp in decode_png or encode_png. Between the setjmp and a jump only
// libpng's frames and functions of this file that hold no object with a destructor run, so the
// jump skips nothing (every buffer lives in the caller, created before the setjmp).
struct Messages {
    std::string error;
};

[[noreturn]] void keep_error(png_structp png, png_const_charp message) {
    static_cast<Messages*>(png_get_error_ptr(png))->error = message ? message : "libpng error";
    png_longjmp(png, 1);
}

void drop_warning(png_structp, png_const_charp) {}  // as OpenImageIO does: not an error

struct MemoryReader {
    const unsigned char* data;
    size_t size, offset;
};

void read_from_memory(png_structp png, png_bytep out, size_t count) {
    auto* reader = static_cast<MemoryReader*>(png_get_io_ptr(png));
    if (count > reader->size - reader->offset) png_error(png, "the file ends early");
    std::memcpy(out, reader->data + reader->offset, count);
    reader->offset += count;
}

// The whole read, between the setjmp and its end: `raw` and `rows` are the caller's.
bool read_png(png_structp png, png_infop info, const DecodeLimits& limits, DecodedFile& out,
              std::vector<unsigned char>& raw, std::vector<png_bytep>& rows, Messages& messages) {
    png_read_info(png, info);
    png_uint_32 width = 0, height = 0;
    int bit_depth = 0, colour_type = 0;
    png_get_IHDR(png, info, &width, &height, &bit_depth, &colour_type, nullptr, nullptr, nullptr);
    if (!within_decode_limits(width, height, limits, messages.error)) return false;
    if (colour_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
    if (colour_type == PNG_COLOR_TYPE_GRAY && bit_depth < 8) png_set_expand_gray_1_2_4_to_8(png);
    if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
    if (bit_depth == 16) png_set_swap(png);  // to this machine's byte order
    (void)png_set_interlace_handling(png);
    png_read_update_info(png, info);

    const int channels = png_get_channels(png, info);
    const bool wide = png_get_bit_depth(png, info) == 16;
    const size_t row_bytes = png_get_rowbytes(png, info);
    raw.resize(row_bytes * height);
    rows.resize(height);
    for (png_uint_32 y = 0; y < height; ++y) rows[y] = raw.data() + y * row_bytes;
    png_read_image(png, rows.data());

    out.width = width;
    out.height = height;
    out.channels = channels;
    out.integer_format = true;
    out.straight_alpha = channels == 2 || channels == 4;
    const size_t count = size_t(width) * height * size_t(channels);
    out.values.resize(count);
    if (wide) {
        for (size_t i = 0; i < count; ++i) {
            uint16_t value;
            std::memcpy(&value, raw.data() + 2 * i, 2);
            out.values[i] = float(value) * (1.0f / 65535.0f);
        }
    } else {
        for (size_t i = 0; i < count; ++i) out.values[i] = float(raw[i]) * (1.0f / 255.0f);
    }
    return true;
}

void write_to_memory(png_structp png, png_bytep data, size_t count) {
    auto* out = static_cast<std::vector<unsigned char>*>(png_get_io_ptr(png));
    bool full = false;  // no exception may cross libpng's frames: it becomes libpng's error
    try {
        out->insert(out->end(), data, data + count);
    } catch (const std::bad_alloc&) {
        full = true;
    }
    if (full) png_error(png, "out of memory");
}

void flush_nothing(png_structp) {}

void write_png(png_structp png, png_infop info, uint32_t width, uint32_t height,
               std::vector<png_bytep>& rows) {
    png_set_IHDR(png, info, width, height, 8, PNG_COLOR_TYPE_RGB_ALPHA, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_set_compression_level(png, 1);
    png_write_info(png, info);
    png_write_image(png, rows.data());
    png_write_end(png, nullptr);
}

}  // namespace

bool is_png(const void* bytes, size_t size) {
    return size >= 8 && png_sig_cmp(static_cast<png_const_bytep>(bytes), 0, 8) == 0;
}

bool decode_png(const void* bytes, size_t size, const DecodeLimits& limits, DecodedFile& out,
                std::string& error) {
    Messages messages;
    MemoryReader reader{static_cast<const unsigned char*>(bytes), size, 0};
    std::vector<unsigned char> raw;
    std::vector<png_bytep> rows;
    png_structp png =
        png_create_read_struct(PNG_LIBPNG_VER_STRING, &messages, keep_error, drop_warning);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!info) {
        png_destroy_read_struct(&png, nullptr, nullptr);
        error = "libpng could not start a reader";
        return false;
    }
    png_set_read_fn(png, &reader, read_from_memory);
    volatile bool ok = false;
    if (setjmp(png_jmpbuf(png)) == 0) ok = read_png(png, info, limits, out, raw, rows, messages);
    png_destroy_read_struct(&png, &info, nullptr);
    if (!ok) error = messages.error.empty() ? "libpng could not decode it" : messages.error;
    return ok;
}

bool encode_png(uint32_t width, uint32_t height, const uint8_t* rgba8,
                std::vector<unsigned char>& out, std::string& error) {
    Messages messages;
    out.clear();
    std::vector<png_bytep> rows(height);
    for (uint32_t y = 0; y < height; ++y)
        rows[y] = const_cast<png_bytep>(rgba8 + size_t(y) * width * 4);
    png_structp png =
        png_create_write_struct(PNG_LIBPNG_VER_STRING, &messages, keep_error, drop_warning);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!info) {
        png_destroy_write_struct(&png, nullptr);
        error = "libpng could not start a writer";
        return false;
    }
    png_set_write_fn(png, &out, write_to_memory, flush_nothing);
    volatile bool ok = false;
    if (setjmp(png_jmpbuf(png)) == 0) {
        write_png(png, info, width, height, rows);
        ok = true;
    }
    png_destroy_write_struct(&png, &info);
    if (!ok) error = messages.error.empty() ? "libpng could not encode it" : messages.error;
    return ok;
}

}  // namespace acetate
