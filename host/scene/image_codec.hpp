#pragma once
// The image file formats themselves (PNG, EXR and whatever else OpenImageIO reads), in a module
// of their own, libacetate-image-codec.so, loaded the first time a file is decoded or encoded.
//
// Why a module: OpenImageIO brings about 260 libraries, and binding them costs every process
// that links it about 0.4 s before main() (measured on the 2-core machine, more than half of a
// short harness case). Most processes of the project never touch an image file: a program
// that embeds the host and renders to its own targets, the harness's `describe` child, a CLI
// run refused for bad input, a test that only reads JSON. Linked into libacetate-host.so they
// paid it anyway; now only a process that reads or writes an image does, once.
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

// The module's functions. Each returns false with a one-line reason in `error` (the caller
// names the file). `name` is the file's path: it picks the format by extension and is what a
// decoder without in-memory input opens.
struct ImageCodec {
    bool (*decode)(const std::string& name, const void* bytes, size_t size,
                   const DecodeLimits& limits, DecodedFile& out, std::string& error);
    // 8-bit straight-alpha sRGB RGBA, as a PNG.
    bool (*encode_png)(const std::string& name, uint32_t width, uint32_t height,
                       const uint8_t* rgba8, std::vector<unsigned char>& out, std::string& error);
    // Float RGBA as an EXR: half (ZIP) or full float (uncompressed, for exact test inputs).
    bool (*encode_exr)(const std::string& name, uint32_t width, uint32_t height, const float* rgba,
                       bool full_float, std::vector<unsigned char>& out, std::string& error);
};

// The module's one entry point (a C name, so the host can find it with dlsym).
extern "C" const ImageCodec* acetate_image_codec();
inline constexpr const char* kImageCodecEntry = "acetate_image_codec";
inline constexpr const char* kImageCodecFile = "libacetate-image-codec.so";

// The codec, the module loaded on the first call (thread-safe; later calls return the same
// table). An error names the module's path and what the dynamic loader said.
Result<const ImageCodec*> image_codec();

}  // namespace acetate
