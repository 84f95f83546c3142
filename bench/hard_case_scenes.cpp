// The hard cases' scenes (hard_cases.hpp): small canvases, every tile drawn 1:1 on whole
// pixels (so drawing a tile copies its texels exactly) and every input value exact in half
// precision (so rgba16f and rgba32f start from the same scene and differ only in what the
// frame stores along the way).

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "hard_cases.hpp"

namespace acetate::bench {
namespace {

namespace fs = std::filesystem;

constexpr float kHalfMax = 65504.0f;

enum class Content {
    Normal,  // alpha 1, 1/2, 1/4 and 0; colours up to 4 (HDR, so bloom has something to do)
    Tiny,    // alpha 2^-24 .. 2^-10, and a block of exactly 2^-24 white
    Huge,    // rgb 65504 at alpha 1
};

Result<void> write_exr(const fs::path& file, const ImageRGBA& image) {
    auto out = OIIO::ImageOutput::create(file.string());
    if (!out) return make_error(ErrorCode::InvalidInput, "cannot create " + file.string());
    OIIO::ImageSpec spec(int(image.width), int(image.height), 4, OIIO::TypeDesc::FLOAT);
    spec.attribute("compression", "none");
    if (!out->open(file.string(), spec) ||
        !out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data()) || !out->close())
        return make_error(ErrorCode::InvalidInput,
                          fmt::format("cannot write {}: {}", file.string(), out->geterror()));
    return {};
}

void set(ImageRGBA& image, uint32_t x, uint32_t y, std::array<float, 4> rgba) {
    float* p = image.at(x, y);
    for (int c = 0; c < 4; ++c) p[c] = round_to_half(rgba[c]);
}

// The tile: premultiplied colour, every value exact in half.
ImageRGBA tile_image(uint32_t w, uint32_t h, Content content) {
    ImageRGBA image(w, h);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            if (content == Content::Tiny) {
                // Every fifth column transparent; the left third exactly 2^-24, white; the
                // rest a ramp 2^-24 .. 2^-10 with colour (1, 1/2, 1/4) premultiplied (rounded
                // to half, so the smallest alphas carry what rgb a half can hold: 0 or 2^-24).
                if (x % 5 == 4) continue;
                if (x < w / 3) {
                    set(image, x, y, {0x1p-24f, 0x1p-24f, 0x1p-24f, 0x1p-24f});
                    continue;
                }
                const float a = std::ldexp(1.0f, -24 + int((x + y) % 15));
                set(image, x, y, {a, 0.5f * a, 0.25f * a, a});
            } else if (content == Content::Huge) {
                const uint32_t block = (x / 4 + y / 4) % 4;
                if (block == 3 && (x + y) % 2) continue;  // transparent pixels among them
                const std::array<float, 3> rgb =
                    block == 0   ? std::array{kHalfMax, kHalfMax, kHalfMax}
                    : block == 1 ? std::array{kHalfMax, 0.0f, 0.0f}
                                 : std::array{0.0f, kHalfMax, kHalfMax};
                set(image, x, y, {rgb[0], rgb[1], rgb[2], 1.0f});
            } else {
                static constexpr float kAlpha[5] = {1.0f, 1.0f, 0.5f, 0.25f, 0.0f};
                const float a = kAlpha[(x / 4 + y / 4) % 5];
                const float shade = 0.25f + float((x * 7 + y * 3) % 8) / 8.0f;
                const bool bright = (x / 8 + y / 8) % 3 == 0 && a == 1.0f;
                const float gain = (bright ? 4.0f : 1.0f) * shade * a;
                set(image, x, y, {0.9f * gain, 0.6f * gain, 0.3f * gain, a});
            }
        }
    return image;
}

ImageRGBA mask_image(uint32_t w, uint32_t h, const std::string& kind) {
    ImageRGBA image(w, h);
    // The fire: a block 6 wide, 4 high, three quarters down, centred (at least one pixel).
    const int fx0 = std::max(0, int(w) / 2 - 3), fx1 = std::min(int(w), int(w) / 2 + 3);
    const int fy0 = std::max(0, int(h) * 3 / 4 - 2), fy1 = std::min(int(h), int(h) * 3 / 4 + 2);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            float v = 0;
            std::array<float, 3> rgb{};
            if (kind == "water") {
                v = x >= w / 8 && x < w - w / 8 && y >= h / 8 && y < h - h / 8 ? 1.0f : 0.0f;
            } else if (kind == "outdoors") {
                v = x < std::max(1u, w / 2) ? 1.0f : 0.0f;
            } else if (kind == "specular") {
                v = 1.0f;
            } else if (kind == "roughness") {
                v = y < h / 2 ? 0.0f : 0.5f;  // 0: clamped to the sharpest lobe
            } else if (kind == "fire") {
                v = int(x) >= fx0 && int(x) < fx1 && int(y) >= fy0 && int(y) < fy1 ? 1.0f : 0.0f;
            }
            if (kind == "normal") {
                // Tilted towards +x and up the image on the right half, flat on the left.
                rgb = x >= w / 2 ? std::array{0.75f, 0.625f, 0.875f} : std::array{0.5f, 0.5f, 1.0f};
            } else {
                rgb = {v, v, v};
            }
            set(image, x, y, {rgb[0], rgb[1], rgb[2], 1.0f});
        }
    return image;
}

std::vector<std::string> masks_of(const std::string& plugin) {
    if (plugin == "acetate.water") return {"water", "outdoors"};
    if (plugin == "acetate.specular") return {"specular", "roughness", "normal"};
    if (plugin == "acetate.fire") return {"fire"};
    return {};
}

double peak_of(const ImageRGBA& image) {
    double peak = 0;
    for (float v : image.pixels) peak = std::max(peak, double(std::fabs(v)));
    return peak;
}

}  // namespace

float round_to_half(float value) {
    const double v = value;
    if (!std::isfinite(v) || v == 0) return value;
    const double magnitude = std::fabs(v);
    // The spacing of halves at v: 2^-24 among the subnormals, 2^(e-10) in [2^e, 2^(e+1)).
    int exp = 0;
    std::frexp(magnitude, &exp);  // magnitude in [2^(exp-1), 2^exp)
    const double spacing = magnitude < 0x1p-14 ? 0x1p-24 : std::ldexp(1.0, exp - 1 - 10);
    const double rounded = std::nearbyint(magnitude / spacing) * spacing;  // ties to even
    if (rounded > 65504.0) return std::copysign(std::numeric_limits<float>::infinity(), value);
    return float(std::copysign(rounded, v));
}

const std::vector<std::string>& hard_case_names() {
    static const std::vector<std::string> names = {
        "alpha 2^-24", "colour 65504", "16 floors", "1x1", "odd 37x23", "odd 1x517", "time 1e5 s"};
    return names;
}

const std::vector<std::string>& shipped_plugins() {
    static const std::vector<std::string> ids = {
        "acetate.lighting", "acetate.bloom", "acetate.water", "acetate.specular", "acetate.fire"};
    return ids;
}

Result<HardCaseScene> make_hard_case_scene(const std::string& plugin, const std::string& hard_case,
                                           const fs::path& dir) {
    const auto& names = hard_case_names();
    if (std::find(names.begin(), names.end(), hard_case) == names.end())
        return make_error(ErrorCode::InvalidInput, fmt::format("no hard case \"{}\"", hard_case));
    uint32_t width = 64, height = 48;
    if (hard_case == "1x1") width = height = 1;
    if (hard_case == "odd 37x23") width = 37, height = 23;
    if (hard_case == "odd 1x517") width = 1, height = 517;
    const Content content = hard_case == "alpha 2^-24"    ? Content::Tiny
                            : hard_case == "colour 65504" ? Content::Huge
                                                          : Content::Normal;
    // Lights bright enough to push 65504 further in the colour case.
    const float intensity = content == Content::Huge ? 1000.0f : 2.0f;
    const bool global = plugin == "acetate.bloom";

    HardCaseScene out;
    out.time = hard_case == "time 1e5 s" ? 1e5 : 2.5;
    SceneDesc& scene = out.scene;
    std::error_code ec;
    fs::create_directories(dir, ec);
    scene.file = dir / "scene.json";
    scene.width = width;
    scene.height = height;
    scene.background = {0, 0, 0, 0};  // transparent: the output shows the contract directly

    // One floor covering the canvas, or 16 floors of one 16x12 tile each on a 4x4 grid (no two
    // overlap, so compositing the floors adds no rounding of its own).
    const bool sixteen = hard_case == "16 floors";
    const int floors = sixteen ? 16 : 1;
    for (int f = 0; f < floors; ++f) {
        const uint32_t tw = sixteen ? 16 : width, th = sixteen ? 12 : height;
        const uint32_t tx = sixteen ? uint32_t(f % 4) * 16 : 0;
        const uint32_t ty = sixteen ? uint32_t(f / 4) * 12 : 0;
        FloorDesc floor;
        floor.name = fmt::format("floor{}", f);
        TileDesc tile;
        const ImageRGBA image = tile_image(tw, th, content);
        out.peak_input = std::max(out.peak_input, peak_of(image));
        tile.image = dir / fmt::format("tile{}.exr", f);
        if (auto written = write_exr(tile.image, image); !written) return written.error();
        tile.rect = {double(tx), double(ty), double(tw), double(th)};
        for (const std::string& kind : masks_of(plugin)) {
            const fs::path file = dir / fmt::format("tile{}_{}.exr", f, kind);
            if (auto written = write_exr(file, mask_image(tw, th, kind)); !written)
                return written.error();
            tile.masks[kind] = file;
        }
        floor.tiles.push_back(tile);
        const float cx = float(tx) + 0.5f * float(tw), cy = float(ty) + 0.5f * float(th);
        const float reach = float(std::max(tw, th));
        LightDesc a;
        a.pos = {cx, cy};
        a.radius = 0.6f * reach + 2.0f;
        a.color = {1.0f, 0.8f, 0.6f};
        a.intensity = intensity;
        a.height = 0.15f * reach;
        LightDesc b;
        b.pos = {float(tx) + 0.25f * float(tw), float(ty) + 0.25f * float(th)};
        b.radius = 0.5f * reach + 1.0f;
        b.color = {0.6f, 0.8f, 1.0f};
        b.intensity = 0.75f * intensity;
        floor.lights = {a, b};
        SunDesc sun;
        sun.azimuth = 135;
        sun.elevation = 40;
        sun.color = {1.0f, 0.9f, 0.7f};
        sun.intensity = content == Content::Huge ? 1000.0f : 3.0f;
        floor.sun = sun;
        if (!global) {
            EffectRef effect;
            effect.plugin = plugin;
            effect.where = fmt::format("floors[{}].effects[0]", f);
            floor.effects.push_back(effect);
        }
        scene.floors.push_back(std::move(floor));
    }
    if (global) {
        EffectRef effect;
        effect.plugin = plugin;
        effect.where = "global_effects[0]";
        scene.global_effects.push_back(effect);
    }
    scene.active_floor = uint32_t(scene.floors.size() - 1);
    return out;
}

}  // namespace acetate::bench
