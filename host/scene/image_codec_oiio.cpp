// libacetate-image-codec.so: the image formats through OpenImageIO (scene/image_codec.hpp says
// why this is a module). Only decoding and encoding live here; the checks on a file's bytes
// and the colour conventions stay in the host (scene/image_io.cpp).

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/typedesc.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "scene/image_codec.hpp"

namespace acetate {
namespace {

// OpenImageIO messages can span lines; ours are one line each.
std::string one_line(std::string text) {
    std::replace(text.begin(), text.end(), '\n', ' ');
    std::replace(text.begin(), text.end(), '\r', ' ');
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return text.empty() ? "unknown OpenImageIO error" : text;
}

// Opens `name` for decoding from `memory`, the file's contents as the host's one input reader
// read them (a regular file, within the size limit), so the decoder never opens a path itself.
// The few formats whose OpenImageIO reader cannot decode from memory open the path, already
// checked. OpenImageIO premultiplies straight-alpha files (PNG, TGA, most TIFF) while reading,
// in the encoded space, which is wrong for an sRGB-encoded image: asking for unassociated alpha
// gets the values as stored, so that decoding can happen before premultiplying.
std::unique_ptr<OIIO::ImageInput> open_input(const std::string& name,
                                             OIIO::Filesystem::IOMemReader& memory) {
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    if (auto input = OIIO::ImageInput::open(name, &config, &memory)) return input;
    (void)OIIO::geterror();  // a reader without memory input, or a bad file: the path tells
    return OIIO::ImageInput::open(name, &config);
}

bool decode(const std::string& name, const void* bytes, size_t size, const DecodeLimits& limits,
            DecodedFile& out, std::string& error) {
    OIIO::Filesystem::IOMemReader memory(bytes, size);
    auto input = open_input(name, memory);
    if (!input) {
        error = one_line(OIIO::geterror());
        return false;
    }
    const OIIO::ImageSpec& spec = input->spec();
    if (spec.deep)
        error = "deep images are not supported";
    else if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
        error = "image has no pixels";
    else if (spec.width > limits.max_side || spec.height > limits.max_side)
        error = "image is " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                ", larger than " + std::to_string(limits.max_side) + " on a side";
    else if (int64_t(spec.width) * spec.height > limits.max_pixels)
        error = "image is " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                ", more than " + std::to_string(limits.max_pixels) + " pixels (8192x8192)";
    if (!error.empty()) return false;

    out.width = uint32_t(spec.width);
    out.height = uint32_t(spec.height);
    out.channels = std::min(spec.nchannels, 4);
    out.values.assign(size_t(spec.width) * spec.height * out.channels, 0.0f);
    // Integer formats come back normalised to [0, 1]; no colour transform happens here.
    if (!input->read_image(0, 0, 0, out.channels, OIIO::TypeDesc::FLOAT, out.values.data())) {
        error = one_line(input->geterror());
        return false;
    }
    out.integer_format = !spec.format.is_floating_point();
    out.straight_alpha = spec.get_int_attribute("oiio:UnassociatedAlpha", 0) == 1;
    input->close();
    return true;
}

// Encodes one image in memory (`format` is "png" or "openexr"); `pixels` are in `pixel_type`.
// Nothing touches the disk here: the host writes the bytes through its one checked, atomic
// writer, so a full disk or a missing folder is an I/O error of the target, and an encoder that
// would not report a short write cannot hide one.
bool encode(const std::string& name, const char* format, const OIIO::ImageSpec& spec,
            OIIO::TypeDesc pixel_type, const void* pixels, std::vector<unsigned char>& out,
            std::string& error) {
    out.clear();
    OIIO::Filesystem::IOVecOutput memory(out);
    auto output = OIIO::ImageOutput::create(format);
    if (!output || !output->set_ioproxy(&memory)) {
        error = std::string("cannot encode ") + format + ": " + one_line(OIIO::geterror());
        return false;
    }
    if (!output->open(name, spec) || !output->write_image(pixel_type, pixels) || !output->close()) {
        error = one_line(output->geterror());
        return false;
    }
    return true;
}

bool encode_png(const std::string& name, uint32_t width, uint32_t height, const uint8_t* rgba8,
                std::vector<unsigned char>& out, std::string& error) {
    OIIO::ImageSpec spec(int(width), int(height), 4, OIIO::TypeDesc::UINT8);
    // Without this OpenImageIO would un-premultiply the already straight values again.
    spec.attribute("oiio:UnassociatedAlpha", 1);
    spec.attribute("oiio:ColorSpace", "sRGB");
    // zlib's fastest level: a quarter of a one-shot render's CPU went to compressing at the
    // default level 6, for files about a tenth smaller (docs/performance.md, "One-shot renders").
    spec.attribute("png:compressionLevel", 1);
    return encode(name, "png", spec, OIIO::TypeDesc::UINT8, rgba8, out, error);
}

bool encode_exr(const std::string& name, uint32_t width, uint32_t height, const float* rgba,
                bool full_float, std::vector<unsigned char>& out, std::string& error) {
    OIIO::ImageSpec spec(int(width), int(height), 4,
                         full_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::HALF);
    if (full_float) spec.attribute("compression", "none");
    return encode(name, "openexr", spec, OIIO::TypeDesc::FLOAT, rgba, out, error);
}

constexpr ImageCodec kCodec{decode, encode_png, encode_exr};

}  // namespace
}  // namespace acetate

extern "C" __attribute__((visibility("default"))) const acetate::ImageCodec* acetate_image_codec() {
    return &acetate::kCodec;
}
