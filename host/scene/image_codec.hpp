#pragma once
// Image formats other than PNG and EXR (JPEG, TIFF, WebP, and whatever else OpenImageIO reads),
// decoded in a module of their own, libacetate-image-codec.so, loaded the first time such a
// file is read. PNG and EXR, the formats Acetate writes and most scenes hold, the host reads and
// writes itself (scene/png_file.hpp, scene/exr_file.hpp).
//
// Why a module: OpenImageIO brings about 260 libraries, and binding them costs every process
// that links it about 0.4 s before main() (measured on the 2-core machine, more than half of a
// short harness case). Linked into libacetate-host.so every process paid it; now only one that
// reads another format does, once.
//
// The module is part of the host, found beside libacetate-host.so (build tree and install
// alike), never named by a scene or a registry; it holds no policy: the host checks every
// file's bytes before they reach it (scene/image_io.cpp) and converts colour after.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/result.hpp"

namespace acetate {

// Pixels as a file stored them: `channels` floats a pixel (1 to 4, the first four of a file
// with more), integer formats normalised to [0, 1], no colour transform.
struct DecodedFile {
    uint32_t width = 0, height = 0;
    int channels = 0;
    std::vector<float> values;    // width * height * channels
    bool integer_format = false;  // uint8/uint16...: sRGB-encoded colour
    bool straight_alpha = false;  // values as stored, alpha not applied
};

// The limits a file is refused beyond, before anything is allocated for its pixels.
struct DecodeLimits {
    int max_side = 0;
    int64_t max_pixels = 0;
};

// Whether a `width` x `height` image is within `limits`; if not, `error` says how, in the same
// words for every format.
inline bool within_decode_limits(int64_t width, int64_t height, const DecodeLimits& limits,
                                 std::string& error) {
    const std::string size = std::to_string(width) + "x" + std::to_string(height);
    if (width <= 0 || height <= 0)
        error = "image has no pixels";
    else if (width > limits.max_side || height > limits.max_side)
        error =
            "image is " + size + ", larger than " + std::to_string(limits.max_side) + " on a side";
    else if (width * height > limits.max_pixels)
        error = "image is " + size + ", more than " + std::to_string(limits.max_pixels) +
                " pixels (8192x8192)";
    else
        return true;
    return false;
}

// The module's functions. `decode` returns false with a one-line reason in `error` (the
// caller names the file). `name` is the file's path: it picks the format by extension and is
// what a decoder without in-memory input opens.
struct ImageCodec {
    bool (*decode)(const std::string& name, const void* bytes, size_t size,
                   const DecodeLimits& limits, DecodedFile& out, std::string& error);
};

// The module's one entry point (a C name, so the host can find it with dlsym).
extern "C" const ImageCodec* acetate_image_codec();
inline constexpr const char* kImageCodecEntry = "acetate_image_codec";
inline constexpr const char* kImageCodecFile = "libacetate-image-codec.so";

// The codec, the module loaded on the first call (thread-safe; later calls return the same
// table). An error names the module's path and what the dynamic loader said.
Result<const ImageCodec*> image_codec();

}  // namespace acetate
