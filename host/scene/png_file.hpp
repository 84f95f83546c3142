#pragma once
// PNG read and written with libpng itself, in the host: the format every render writes and most
// tiles are, without loading OpenImageIO (scene/image_codec.hpp) for it. Decoding gives what
// OpenImageIO's PNG reader gives, value for value: palettes expanded to RGB, grey below 8 bits
// to 8, a tRNS chunk to an alpha channel, the stored values as they are (no gamma applied, alpha
// straight), each channel scaled to [0, 1] as OpenImageIO scales it (k * (1/255) or
// k * (1/65535)). Nothing is printed: libpng's errors and warnings come back as text.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "scene/image_codec.hpp"

namespace acetate {

// Whether `bytes` start with the PNG signature.
bool is_png(const void* bytes, size_t size);

// Decodes a PNG held in memory; false with a one-line reason in `error`. Sizes beyond `limits`
// are refused from the header, before the pixels are allocated.
bool decode_png(const void* bytes, size_t size, const DecodeLimits& limits, DecodedFile& out,
                std::string& error);

// Encodes 8-bit straight-alpha sRGB RGBA as a PNG (zlib's fastest level: docs/performance.md,
// "One-shot renders"), with an sRGB chunk.
bool encode_png(uint32_t width, uint32_t height, const uint8_t* rgba8,
                std::vector<unsigned char>& out, std::string& error);

}  // namespace acetate
