#pragma once
// Image files in and out: PNG and EXR by libpng and OpenEXR in the host (scene/png_file.hpp,
// scene/exr_file.hpp), any other format read by OpenImageIO in a module loaded when one is met
// (scene/image_codec.hpp). Colour inside the host is linear light, premultiplied RGBA float;
// masks are data (docs/design.md, "Conventions").

#include <cstdint>
#include <filesystem>
#include <vector>

#include "core/image_rgba.hpp"
#include "core/result.hpp"
#include "scene/srgb.hpp"  // the transfer curve the files use

namespace acetate {

enum class ImageRole {
    Colour,  // integer formats are sRGB-decoded; straight alpha is premultiplied after decoding;
             // associated-alpha files (EXR) are taken as they are
    Mask,    // data: no colour decode, no premultiplication; integer formats scaled to [0, 1]
};

// Loads PNG, JPEG, WebP, TIFF, EXR (anything OpenImageIO reads). Images without alpha get
// a = 1; single-channel images are replicated to RGB. Error names the file.
Result<ImageRGBA> load_image(const std::filesystem::path& file, ImageRole role);

// Writes by extension: `.exr` = half-float, premultiplied, linear; `.png` = 8-bit sRGB,
// straight alpha (un-premultiplied safely: no division at alpha that rounds to 0 in 8 bits, no
// NaN). The file is written to a temporary name and renamed, so a reader never sees half a file.
Result<void> save_image(const std::filesystem::path& file, const ImageRGBA& image);

// Converts premultiplied linear RGBA to straight-alpha 8-bit sRGB (what `.png` holds).
// Where the 8-bit alpha is 0 the colour is 0; colour is clamped to [0, 1] before encoding.
void premultiplied_to_srgb8(const float in[4], uint8_t out[4]);

}  // namespace acetate
