#pragma once
// OpenEXR read and written with the OpenEXR library itself, in the host, without loading
// OpenImageIO (scene/image_codec.hpp) for it. Decoding gives RGBA floats of the data window, as
// OpenImageIO's reader does for the files Acetate reads and writes: R, G, B and A as stored (a
// missing A is 1), luminance-only files as grey. A file with none of R, G, B, A or Y is refused
// rather than read as black. No thread is started (OpenEXR's pool stays empty), so a forked
// process can decode.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "scene/image_codec.hpp"

namespace acetate {

// Whether `bytes` start with OpenEXR's magic number.
bool is_exr(const void* bytes, size_t size);

// Decodes an EXR held in memory into four channels; false with a one-line reason in `error`.
// Sizes beyond `limits` are refused from the header, before the pixels are allocated.
bool decode_exr(const void* bytes, size_t size, const DecodeLimits& limits, DecodedFile& out,
                std::string& error);

// Encodes RGBA floats as an EXR: half-float with ZIP compression (what `.exr` outputs are), or
// full float uncompressed (`full_float`: exact, for test inputs).
bool encode_exr(uint32_t width, uint32_t height, const float* rgba, bool full_float,
                std::vector<unsigned char>& out, std::string& error);

}  // namespace acetate
