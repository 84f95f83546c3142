#include "scene/image_io.hpp"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/typedesc.h>
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "core/atomic_file.hpp"
#include "core/input_file.hpp"
#include "core/stderr_capture.hpp"
#include "scene/exr_header_check.hpp"
#include "scene/png_chunk_check.hpp"

namespace acetate {
namespace {

namespace fs = std::filesystem;

// Far above any device limit; stops a corrupt header from asking for terabytes.
constexpr int kMaxImageSide = 65536;
// At most 2^26 pixels (8192x8192): decoding needs 32 bytes a pixel (the decoded floats and the
// RGBA image), so 2 GiB at most, and a small compressed file declaring a huge image (a
// decompression bomb) is refused before anything is allocated.
constexpr int64_t kMaxImagePixels = int64_t(1) << 26;
// The largest finite half-float; larger values would turn into Inf when written to EXR.
constexpr float kHalfMax = 65504.0f;

// OpenImageIO messages can span lines; ours are one line each.
std::string one_line(std::string text) {
    std::replace(text.begin(), text.end(), '\n', ' ');
    std::replace(text.begin(), text.end(), '\r', ' ');
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return text.empty() ? "unknown OpenImageIO error" : text;
}

Error file_error(ErrorCode code, const fs::path& file, const std::string& what) {
    return make_error(code, fmt::format("{}: {}", file.string(), one_line(what)));
}

// What OpenImageIO handed back, before Acetate's colour conventions are applied.
struct DecodedPixels {
    ImageRGBA image;
    bool has_alpha = false;
    bool integer_format = false;  // uint8/uint16...: sRGB-encoded colour
    bool straight_alpha = false;  // OpenImageIO returned unassociated values
};

// Opens `file` for decoding from `memory`, its contents as the project's one input reader read
// them (a regular file, within the size limit), so the decoder never opens a path itself. The
// few formats whose OpenImageIO reader cannot decode from memory open the path, already
// checked. OpenImageIO premultiplies straight-alpha files (PNG, TGA, most TIFF) while reading,
// in the encoded space, which is wrong for an sRGB-encoded image: asking for unassociated alpha
// gets the values as stored, so that decoding can happen before premultiplying.
std::unique_ptr<OIIO::ImageInput> open_input(const fs::path& file,
                                             OIIO::Filesystem::IOMemReader& memory) {
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    if (auto input = OIIO::ImageInput::open(file.string(), &config, &memory)) return input;
    (void)OIIO::geterror();  // a reader without memory input, or a bad file: the path tells
    return OIIO::ImageInput::open(file.string(), &config);
}

// Channel layout rules: 1 = grey, 2 = grey + alpha, 3 = RGB, 4+ = the first four as RGBA.
void expand_to_rgba(const std::vector<float>& source, int channels, ImageRGBA& image) {
    const size_t pixel_count = size_t(image.width) * image.height;
    for (size_t i = 0; i < pixel_count; ++i) {
        const float* in = &source[i * size_t(channels)];
        float* out = &image.pixels[i * 4];
        if (channels <= 2) {
            out[0] = out[1] = out[2] = in[0];
            out[3] = channels == 2 ? in[1] : 1.0f;
        } else {
            std::copy(in, in + 3, out);
            out[3] = channels >= 4 ? in[3] : 1.0f;
        }
    }
}

Result<DecodedPixels> read_pixels(OIIO::ImageInput& input, const fs::path& file) {
    const OIIO::ImageSpec& spec = input.spec();
    if (spec.deep) return file_error(ErrorCode::ImageDecode, file, "deep images are not supported");
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
        return file_error(ErrorCode::ImageDecode, file, "image has no pixels");
    if (spec.width > kMaxImageSide || spec.height > kMaxImageSide)
        return file_error(ErrorCode::ImageDecode, file,
                          fmt::format("image is {}x{}, larger than {} on a side", spec.width,
                                      spec.height, kMaxImageSide));
    if (int64_t(spec.width) * spec.height > kMaxImagePixels)
        return file_error(ErrorCode::ImageDecode, file,
                          fmt::format("image is {}x{}, more than {} pixels (8192x8192)", spec.width,
                                      spec.height, kMaxImagePixels));

    const int channels = std::min(spec.nchannels, 4);
    std::vector<float> source(size_t(spec.width) * spec.height * channels);
    // Integer formats come back normalised to [0, 1]; no colour transform happens here.
    if (!input.read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, source.data()))
        return file_error(ErrorCode::ImageDecode, file, input.geterror());

    DecodedPixels decoded;
    decoded.image = ImageRGBA(uint32_t(spec.width), uint32_t(spec.height));
    expand_to_rgba(source, channels, decoded.image);
    decoded.has_alpha = channels == 2 || channels == 4;
    decoded.integer_format = !spec.format.is_floating_point();
    decoded.straight_alpha = spec.get_int_attribute("oiio:UnassociatedAlpha", 0) == 1;
    return decoded;
}

// The contract forbids NaN and Inf anywhere; a float file can hold them, so it is refused
// here with the first offending pixel rather than poisoning every effect downstream.
Result<void> check_finite(const ImageRGBA& image, const fs::path& file) {
    for (size_t i = 0; i < image.pixels.size(); ++i) {
        if (std::isfinite(image.pixels[i])) continue;
        const size_t pixel = i / 4;
        return file_error(
            ErrorCode::ImageDecode, file,
            fmt::format("pixel ({}, {}) channel {} is {}; images must be finite",
                        pixel % image.width, pixel / image.width, i % 4, image.pixels[i]));
    }
    return {};
}

// Colour role: linear light, premultiplied.
void to_linear_premultiplied(DecodedPixels& decoded) {
    // A reader that ignored our request (WebP) premultiplied in encoded space; undo that
    // first so the sRGB curve sees the stored colour.
    const bool undo_encoded_premultiply =
        decoded.integer_format && decoded.has_alpha && !decoded.straight_alpha;
    const bool premultiply =
        decoded.has_alpha && (decoded.integer_format || decoded.straight_alpha);
    std::vector<float>& px = decoded.image.pixels;
    for (size_t i = 0; i < px.size(); i += 4) {
        const float alpha = px[i + 3];
        for (size_t c = 0; c < 3; ++c) {
            float value = px[i + c];
            if (undo_encoded_premultiply)
                value = alpha > 0.0f ? std::min(value / alpha, 1.0f) : 0.0f;
            if (decoded.integer_format) value = srgb_to_linear(value);
            if (premultiply) value *= alpha;
            px[i + c] = value;
        }
    }
}

// Encodes one image in memory with OpenImageIO (`format` is "png" or "openexr"); `pixels` are
// in `pixel_type`. Nothing touches the disk here: the bytes then go through the project's one
// checked, atomic writer, so a full disk or a missing folder is an I/O error of the target, and
// an encoder that would not report a short write cannot hide one.
Result<std::vector<unsigned char>> encode_with_oiio(const fs::path& file, const char* format,
                                                    const OIIO::ImageSpec& spec,
                                                    OIIO::TypeDesc pixel_type, const void* pixels) {
    std::vector<unsigned char> bytes;
    OIIO::Filesystem::IOVecOutput memory(bytes);
    auto output = OIIO::ImageOutput::create(format);
    if (!output || !output->set_ioproxy(&memory))
        return file_error(ErrorCode::ImageEncode, file,
                          fmt::format("cannot encode {}: {}", format, OIIO::geterror()));
    if (!output->open(file.string(), spec) || !output->write_image(pixel_type, pixels) ||
        !output->close())
        return file_error(ErrorCode::ImageEncode, file, output->geterror());
    return bytes;
}

Result<std::vector<unsigned char>> encode_exr(const fs::path& file, const ImageRGBA& image) {
    // Premultiplied linear, as the host holds it; only values beyond the half range are
    // clamped, so that the conversion does not create Inf.
    std::vector<float> pixels(image.pixels);
    for (float& value : pixels)
        if (std::isfinite(value)) value = std::clamp(value, -kHalfMax, kHalfMax);
    OIIO::ImageSpec spec(int(image.width), int(image.height), 4, OIIO::TypeDesc::HALF);
    return encode_with_oiio(file, "openexr", spec, OIIO::TypeDesc::FLOAT, pixels.data());
}

Result<std::vector<unsigned char>> encode_png(const fs::path& file, const ImageRGBA& image) {
    std::vector<uint8_t> pixels(image.pixels.size());
    for (size_t i = 0; i < image.pixels.size(); i += 4)
        premultiplied_to_srgb8(&image.pixels[i], &pixels[i]);
    OIIO::ImageSpec spec(int(image.width), int(image.height), 4, OIIO::TypeDesc::UINT8);
    // Without this OpenImageIO would un-premultiply the already straight values again.
    spec.attribute("oiio:UnassociatedAlpha", 1);
    spec.attribute("oiio:ColorSpace", "sRGB");
    // zlib's fastest level: a quarter of a one-shot render's CPU went to compressing at the
    // default level 6, for files about a tenth smaller (docs/performance.md, "One-shot renders").
    spec.attribute("png:compressionLevel", 1);
    return encode_with_oiio(file, "png", spec, OIIO::TypeDesc::UINT8, pixels.data());
}

}  // namespace

void premultiplied_to_srgb8(const float in[4], uint8_t out[4]) {
    const float alpha = std::isnan(in[3]) ? 0.0f : std::clamp(in[3], 0.0f, 1.0f);
    const long alpha8 = std::lround(alpha * 255.0f);
    out[3] = uint8_t(alpha8);
    // Dividing by an alpha that the file cannot hold anyway would only amplify noise.
    if (alpha8 == 0) {
        out[0] = out[1] = out[2] = 0;
        return;
    }
    for (int c = 0; c < 3; ++c) {
        // Divide by the true alpha, not the rounded one: the stored colour is then the real
        // straight colour, and a valid premultiplied pixel (rgb <= a) needs no clamping.
        float straight = in[c] / alpha;
        straight = std::isnan(straight) ? 0.0f : std::clamp(straight, 0.0f, 1.0f);
        out[c] = linear_to_srgb8(straight);
    }
}

Result<ImageRGBA> load_image(const fs::path& file, ImageRole role) {
    auto bytes = read_input_file(file, kMaxImageFileBytes, "an image");
    if (!bytes) return bytes.error();
    ACETATE_TRY(check_exr_header(bytes.value(), file, kMaxImageSide));
    ACETATE_TRY(check_png_chunks(bytes.value(), file));
    OIIO::Filesystem::IOMemReader memory(bytes->data(), bytes->size());
    // libpng and others print raw lines of their own before failing; the failure is reported
    // below in one line, so what they printed is dropped then, and passed on as one line when
    // the image decodes anyway (a warning).
    StderrCapture library_output;
    auto input = open_input(file, memory);
    if (!input) {
        const std::string why = OIIO::geterror();
        library_output.finish();
        return file_error(ErrorCode::ImageDecode, file, why);
    }
    auto decoded = read_pixels(*input, file);
    input->close();
    const std::string printed = library_output.finish();
    if (!decoded) return decoded.error();
    if (!printed.empty())
        std::fprintf(stderr, "acetate: warning: %s: the decoder said: %s\n", file.c_str(),
                     one_line(printed).c_str());
    ACETATE_TRY(check_finite(decoded->image, file));
    // Masks are data (water depth, roughness...): values stay as stored.
    if (role == ImageRole::Colour) to_linear_premultiplied(*decoded);
    return std::move(decoded->image);
}

Result<void> save_image(const fs::path& file, const ImageRGBA& image) {
    if (image.width == 0 || image.height == 0 ||
        image.pixels.size() != size_t(image.width) * image.height * 4)
        return file_error(ErrorCode::InvalidInput, file,
                          fmt::format("cannot save a {}x{} image holding {} floats", image.width,
                                      image.height, image.pixels.size()));
    // Exactly these two extensions, as the docs say: ".PNG" is refused, not guessed at.
    const std::string extension = file.extension().string();
    const bool exr = extension == ".exr";
    if (!exr && extension != ".png")
        return file_error(
            ErrorCode::InvalidInput, file,
            fmt::format("unsupported output extension \"{}\" (supported: .exr, .png)", extension));
    auto encoded = exr ? encode_exr(file, image) : encode_png(file, image);
    if (!encoded) return encoded.error();
    const auto& bytes = encoded.value();
    return write_file_atomically(
        file, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

}  // namespace acetate
