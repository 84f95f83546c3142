// libacetate-image-codec.so: the image formats other than PNG and EXR, through OpenImageIO
// (scene/image_codec.hpp says why this is a module). Only decoding lives here; the checks on a
// file's bytes and the colour conventions stay in the host (scene/image_io.cpp).

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
    if (spec.deep) {
        error = "deep images are not supported";
        return false;
    }
    if (spec.nchannels <= 0) {
        error = "image has no pixels";
        return false;
    }
    if (!within_decode_limits(spec.width, spec.height, limits, error)) return false;

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

constexpr ImageCodec kCodec{decode};

}  // namespace
}  // namespace acetate

extern "C" __attribute__((visibility("default"))) const acetate::ImageCodec* acetate_image_codec() {
    return &acetate::kCodec;
}
