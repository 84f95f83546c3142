#include "scene/image_io.hpp"

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
#include "scene/exr_file.hpp"
#include "scene/exr_header_check.hpp"
#include "scene/image_codec.hpp"
#include "scene/png_chunk_check.hpp"
#include "scene/png_file.hpp"

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

// What a decoder printed can span lines; ours are one line each.
std::string one_line(std::string text) {
    std::replace(text.begin(), text.end(), '\n', ' ');
    std::replace(text.begin(), text.end(), '\r', ' ');
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return text.empty() ? "unknown decoder error" : text;
}

Error file_error(ErrorCode code, const fs::path& file, const std::string& what) {
    return make_error(code, fmt::format("{}: {}", file.string(), one_line(what)));
}

// What the codec handed back, before Acetate's colour conventions are applied.
struct DecodedPixels {
    ImageRGBA image;
    bool has_alpha = false;
    bool integer_format = false;  // uint8/uint16...: sRGB-encoded colour
    bool straight_alpha = false;  // unassociated values, as stored
};

// Channel layout rules: 1 = grey, 2 = grey + alpha, 3 = RGB, 4+ = the first four as RGBA.
DecodedPixels expand_to_rgba(const DecodedFile& file) {
    DecodedPixels decoded;
    decoded.image = ImageRGBA(file.width, file.height);
    const int channels = file.channels;
    const size_t pixel_count = size_t(file.width) * file.height;
    for (size_t i = 0; i < pixel_count; ++i) {
        const float* in = &file.values[i * size_t(channels)];
        float* out = &decoded.image.pixels[i * 4];
        if (channels <= 2) {
            out[0] = out[1] = out[2] = in[0];
            out[3] = channels == 2 ? in[1] : 1.0f;
        } else {
            std::copy(in, in + 3, out);
            out[3] = channels >= 4 ? in[3] : 1.0f;
        }
    }
    decoded.has_alpha = channels == 2 || channels == 4;
    decoded.integer_format = file.integer_format;
    decoded.straight_alpha = file.straight_alpha;
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

Result<std::vector<unsigned char>> encode_exr_bytes(const fs::path& file, const ImageRGBA& image) {
    // Premultiplied linear, as the host holds it; only values beyond the half range are
    // clamped, so that the conversion does not create Inf.
    std::vector<float> pixels(image.pixels);
    for (float& value : pixels)
        if (std::isfinite(value)) value = std::clamp(value, -kHalfMax, kHalfMax);
    std::vector<unsigned char> bytes;
    std::string why;
    if (!encode_exr(image.width, image.height, pixels.data(), false, bytes, why))
        return file_error(ErrorCode::ImageEncode, file, why);
    return bytes;
}

Result<std::vector<unsigned char>> encode_png_bytes(const fs::path& file, const ImageRGBA& image) {
    std::vector<uint8_t> pixels(image.pixels.size());
    for (size_t i = 0; i < image.pixels.size(); i += 4)
        premultiplied_to_srgb8(&image.pixels[i], &pixels[i]);
    std::vector<unsigned char> bytes;
    std::string why;
    if (!encode_png(image.width, image.height, pixels.data(), bytes, why))
        return file_error(ErrorCode::ImageEncode, file, why);
    return bytes;
}

// Decodes `bytes` of `file`: PNG and EXR by the host itself, any other format by the codec
// module (loaded now if it is not yet). False with the reason in `why`.
bool decode_file(const fs::path& file, const std::string& bytes, DecodedFile& stored,
                 std::string& why) {
    const DecodeLimits limits{kMaxImageSide, kMaxImagePixels};
    if (is_png(bytes.data(), bytes.size()))
        return decode_png(bytes.data(), bytes.size(), limits, stored, why);
    if (is_exr(bytes.data(), bytes.size()))
        return decode_exr(bytes.data(), bytes.size(), limits, stored, why);
    auto codec = image_codec();
    if (!codec) {
        why = codec.error().message;
        return false;
    }
    return codec.value()->decode(file.string(), bytes.data(), bytes.size(), limits, stored, why);
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
    // libpng and others print raw lines of their own before failing; the failure is reported
    // below in one line, so what they printed is dropped then, and passed on as one line when
    // the image decodes anyway (a warning).
    StderrCapture library_output;
    DecodedFile stored;
    std::string why;
    const bool ok = decode_file(file, bytes.value(), stored, why);
    const std::string printed = library_output.finish();
    if (!ok) return file_error(ErrorCode::ImageDecode, file, why);
    DecodedPixels decoded = expand_to_rgba(stored);
    if (!printed.empty())
        std::fprintf(stderr, "acetate: warning: %s: the decoder said: %s\n", file.c_str(),
                     one_line(printed).c_str());
    ACETATE_TRY(check_finite(decoded.image, file));
    // Masks are data (water depth, roughness...): values stay as stored.
    if (role == ImageRole::Colour) to_linear_premultiplied(decoded);
    return std::move(decoded.image);
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
    auto encoded = exr ? encode_exr_bytes(file, image) : encode_png_bytes(file, image);
    if (!encoded) return encoded.error();
    const auto& bytes = encoded.value();
    return write_file_atomically(
        file, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

}  // namespace acetate
