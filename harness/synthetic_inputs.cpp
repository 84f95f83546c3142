#include "synthetic_inputs.hpp"

#include <Imath/half.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "core/atomic_file.hpp"

namespace acetate::harness {
namespace {

using nlohmann::json;
constexpr double kTau = 6.283185307179586;

// A smooth straight-alpha colour in [0.1, 0.9], different per floor and seed.
std::array<float, 3> colour_at(double u, double v, const std::array<double, 3>& phase) {
    return {float(0.5 + 0.4 * std::sin(kTau * (u + phase[0]))),
            float(0.5 + 0.4 * std::sin(kTau * (v + phase[1]))),
            float(0.5 + 0.4 * std::sin(kTau * (u + v + phase[2])))};
}

void put(ImageRGBA& image, uint32_t x, uint32_t y, const std::array<float, 3>& straight, float a) {
    float* p = image.at(x, y);
    for (int c = 0; c < 3; ++c) p[c] = straight[c] * a;
    p[3] = a;
}

// Opaque on the left third, alpha = v in the middle (down to nearly 0 at the top), a checker
// of 0.5 and 0 on the right: every kind of coverage a floor can have, in one tile.
void standard(ImageRGBA& image, const std::array<double, 3>& phase, bool opaque) {
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x) {
            const double u = (x + 0.5) / image.width, v = (y + 0.5) / image.height;
            float a = 1.0f;
            if (!opaque && u >= 2.0 / 3.0)
                a = ((x / 8 + y / 8) % 2) ? 0.5f : 0.0f;
            else if (!opaque && u >= 1.0 / 3.0)
                a = float(v);
            put(image, x, y, colour_at(u, v, phase), a);
        }
}

// Alpha 2^(-16 u): 1 at the left edge down to 1/65535 at the right.
void alpha_ramp(ImageRGBA& image, const std::array<double, 3>& phase) {
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x) {
            const double u = image.width > 1 ? double(x) / (image.width - 1) : 1.0;
            const float a = std::max(float(std::exp2(-16.0 * u)), 1.0f / 65535.0f);
            put(image, x, y, colour_at(u, (y + 0.5) / image.height, phase), a);
        }
}

// 8x8 blocks of premultiplied values from 1 up to 65504 (the half-float maximum); every third
// block half transparent, every fifth transparent.
void hdr(ImageRGBA& image) {
    constexpr float levels[] = {1.0f, 100.0f, 1000.0f, 16384.0f, 32768.0f, 60000.0f, 65504.0f};
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x) {
            const uint32_t block = x / 8 + 3 * (y / 8);
            const float level = levels[block % 7];
            const float a = block % 5 == 4 ? 0.0f : block % 3 == 2 ? 0.5f : 1.0f;
            float* p = image.at(x, y);
            const float rgb[3] = {level, level * 0.5f, level * 0.25f};
            for (int c = 0; c < 3; ++c) p[c] = a == 0 ? 0.0f : rgb[c] * std::min(1.0f, a * 2);
            p[3] = a;
        }
}

// 8x8 blocks of tiny alphas (the smallest half-float subnormal 2^-24, 2^-23, 2^-20, the
// smallest normal 2^-14, 2^-11) and some ordinary ones, each under straight colour from 0.5 to
// 1000: premultiplied, colour far above alpha, as HDR light on a faint edge gives.
void subnormal(ImageRGBA& image) {
    constexpr float alphas[] = {0x1p-24f, 0x1p-23f, 0x1p-20f, 0x1p-14f, 0x1p-11f, 0.5f, 1.0f, 0.0f};
    constexpr float colours[] = {0.5f, 1.0f, 1000.0f};
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x) {
            const uint32_t block = x / 8 + 5 * (y / 8);
            const float a = alphas[block % 8], c = colours[(block / 8) % 3];
            put(image, x, y, {c, c * 0.5f, c * 0.25f}, a);
        }
}

// The floor's lights, by kind: three over the canvas reaching most of it, none, one at the
// centre, 100, three off the canvas reaching onto it, three with a radius of 10^-4 pixels,
// three with a radius of 10^6.
std::vector<LightDesc> make_lights(LightSet kind, uint32_t w, uint32_t h, std::mt19937_64& rng) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const double reach = std::max(w, h);
    auto light = [&](double x, double y, double radius) {
        LightDesc l;
        l.pos = {float(x), float(y)};
        l.radius = float(radius);
        l.color = {float(0.5 + 0.5 * unit(rng)), float(0.5 + 0.5 * unit(rng)),
                   float(0.5 + 0.5 * unit(rng))};
        l.intensity = float(0.5 + 1.5 * unit(rng));
        // Heights from 0 to 0.6 radius, a function of the position rather than another random
        // draw, so the other values stay what earlier versions of the harness used.
        const double spread = x * 0.37 + y * 0.11;
        l.height = float(radius * 0.6 * (spread - std::floor(spread)));
        return l;
    };
    auto inside = [&](double radius) {
        const double x = unit(rng) * w, y = unit(rng) * h;
        return light(x, y, radius);
    };
    std::vector<LightDesc> lights;
    switch (kind) {
        case LightSet::Standard:
            for (int i = 0; i < 3; ++i)
                lights.push_back(inside(1.0 + reach * (0.3 + 0.4 * unit(rng))));
            break;
        case LightSet::None:
            break;
        case LightSet::One:
            lights.push_back(light(w * 0.5, h * 0.5, 1.0 + reach * 0.5));
            break;
        case LightSet::Many:
            for (int i = 0; i < 100; ++i) lights.push_back(inside(1.0 + reach * 0.2 * unit(rng)));
            break;
        case LightSet::OffCanvas:
            lights.push_back(light(-0.5 * w, 0.5 * h, 1.0 + reach));
            lights.push_back(light(1.5 * w, -0.5 * h, 1.0 + reach));
            lights.push_back(light(0.5 * w, 1.0e4 + h, 2.0e4));
            break;
        case LightSet::Tiny:
            for (int i = 0; i < 3; ++i) lights.push_back(inside(1.0e-4));
            break;
        case LightSet::Huge:
            for (int i = 0; i < 3; ++i) lights.push_back(inside(1.0e6));
            break;
        case LightSet::Sun:
            for (int i = 0; i < 3; ++i)
                lights.push_back(inside(1.0 + reach * (0.3 + 0.4 * unit(rng))));
            break;
        case LightSet::GrazingSun:
        case LightSet::ZenithSun:
            lights.push_back(light(w * 0.5, h * 0.5, 1.0 + reach * 0.5));
            break;
        case LightSet::OnTheFloor:
            // On the floor (height exactly 0), at whole-pixel corners: the canvas's top-left
            // and bottom-right corners and the whole pixel nearest its centre.
            for (const auto& [x, y] : {std::pair{0.0, 0.0}, std::pair{double(w), double(h)},
                                       std::pair{std::round(w * 0.5), std::round(h * 0.5)}}) {
                LightDesc l = light(x, y, 1.0 + reach * 0.5);
                l.height = 0.0f;
                lights.push_back(l);
            }
            break;
        case LightSet::Dark:
            // What the format allows at the bottom of colour and intensity: zero.
            for (int i = 0; i < 3; ++i) {
                LightDesc l = inside(1.0 + reach * (0.3 + 0.4 * unit(rng)));
                if (i != 1) l.color = {0.0f, 0.0f, 0.0f};
                if (i != 0) l.intensity = 0.0f;
                lights.push_back(l);
            }
            break;
    }
    return lights;
}

std::array<uint32_t, 4> floor_rect(uint32_t w, uint32_t h, uint32_t floor) {
    if (floor == 0) return {0, 0, w, h};
    auto part = [](uint32_t size, double f) { return uint32_t(std::floor(size * f)); };
    if (floor % 2 == 1) {  // upper right
        const uint32_t x0 = std::min(part(w, 0.3), w - 1);
        return {x0, 0, w - x0, std::max(1u, part(h, 0.7))};
    }
    const uint32_t y0 = std::min(part(h, 0.35), h - 1);  // lower left
    return {0, y0, std::max(1u, part(w, 0.6)), h - y0};
}

}  // namespace

void round_to_half(ImageRGBA& image) {
    for (float& v : image.pixels) v = float(Imath::half(v));
}

FloorInput make_floor_input(Pattern pattern, uint32_t canvas_width, uint32_t canvas_height,
                            uint32_t floor, uint32_t floors, uint64_t seed,
                            const std::vector<std::string>& mask_kinds) {
    return make_floor_input(InputChoice{pattern}, canvas_width, canvas_height, floor, floors, seed,
                            mask_kinds);
}

FloorInput make_floor_input(const InputChoice& choice, uint32_t canvas_width,
                            uint32_t canvas_height, uint32_t floor, uint32_t floors, uint64_t seed,
                            const std::vector<std::string>& mask_kinds) {
    const Pattern pattern = choice.pattern;
    std::mt19937_64 rng(seed + 7919 * floor);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    FloorInput in;
    const auto rect = floor_rect(canvas_width, canvas_height, floors == 1 ? 0 : floor);
    in.x = rect[0];
    in.y = rect[1];
    in.width = rect[2];
    in.height = rect[3];
    in.image = ImageRGBA(in.width, in.height);
    const std::array<double, 3> phase{unit(rng), unit(rng), unit(rng)};
    switch (pattern) {
        case Pattern::Standard:
            standard(in.image, phase, false);
            break;
        case Pattern::Opaque:
            standard(in.image, phase, true);
            break;
        case Pattern::AlphaRamp:
            alpha_ramp(in.image, phase);
            break;
        case Pattern::Hdr:
            hdr(in.image);
            break;
        case Pattern::Empty:
            break;  // all zero
        case Pattern::Subnormal:
            subnormal(in.image);
            break;
    }
    round_to_half(in.image);

    // Masks vary across the tile so that a mask-driven parameter has something to act on.
    for (const std::string& kind :
         choice.masks == MaskFill::Absent ? std::vector<std::string>{} : mask_kinds) {
        ImageRGBA mask(in.width, in.height);
        const double offset = unit(rng) * kTau;
        for (uint32_t y = 0; y < in.height; ++y)
            for (uint32_t x = 0; x < in.width; ++x) {
                float m = float(0.5 + 0.5 * std::sin(0.21 * x + 0.13 * y + offset));
                if (choice.masks == MaskFill::Empty) m = 0.0f;
                if (choice.masks == MaskFill::Full) m = 1.0f;
                if (choice.masks == MaskFill::Partial && 2 * x >= in.width) m = 0.0f;
                if (choice.masks == MaskFill::AboveOne) m = 1.0f + 3.0f * m;
                // One-pixel lines: the tile's edges, and a row and a column through it.
                if (choice.masks == MaskFill::Thin)
                    m = x == 0 || y == 0 || x + 1 == in.width || y + 1 == in.height ||
                                x == in.width / 3 || y == in.height / 2
                            ? 1.0f
                            : 0.0f;
                std::fill_n(mask.at(x, y), 4, m);
            }
        round_to_half(mask);
        in.masks[kind] = std::move(mask);
    }
    in.lights = make_lights(choice.lights, canvas_width, canvas_height, rng);
    if (choice.lights == LightSet::Sun) in.sun = SunDesc{30, 40, {1.0f, 0.95f, 0.8f}, 1.5f};
    if (choice.lights == LightSet::GrazingSun) in.sun = SunDesc{200, 0, {1.0f, 0.6f, 0.3f}, 2.0f};
    // Overhead, at an azimuth a whole turn below 0 (any finite azimuth is allowed).
    if (choice.lights == LightSet::ZenithSun) in.sun = SunDesc{-360, 90, {1.0f, 1.0f, 0.9f}, 1.0f};
    if (choice.lights == LightSet::Dark) in.sun = SunDesc{120, 30, {0.0f, 0.0f, 0.0f}, 0.0f};
    switch (choice.floor_variant) {
        case FloorVariant::LongNames:  // 300 characters, unique by their end
            in.name = std::string(296, 'f') + fmt::format("{:04}", floor);
            break;
        case FloorVariant::UnicodeNames:  // UTF-8 beyond ASCII: accents, CJK, an emoji
            in.name = fmt::format("\u00e9tage-\u5730\u9762-\U0001f30a-{}", floor);
            break;
        default:
            in.name = fmt::format("floor{}", floor);
    }
    if (choice.floor_variant == FloorVariant::TopFloorEmpty && floor + 1 == floors && floors > 1)
        in.tiled = false;
    return in;
}

Result<SceneDesc> write_scene(const SceneLayout& layout, const std::filesystem::path& where,
                              const std::string& name) {
    const std::filesystem::path directory = std::filesystem::absolute(where);
    auto effects_json = [](const std::vector<SceneEffect>& effects) {
        json out = json::array();
        for (const SceneEffect& e : effects) {
            json effect = {{"plugin", e.plugin}, {"params", e.params}};
            if (!e.preset.empty()) effect["preset"] = e.preset;
            out.push_back(effect);
        }
        return out;
    };
    json floors = json::array();
    for (size_t f = 0; f < layout.floors.size(); ++f) {
        const FloorInput& in = layout.floors[f];
        const std::string floor_name = in.name.empty() ? fmt::format("floor{}", f) : in.name;
        json lights = json::array();
        for (const LightDesc& l : in.lights)
            lights.push_back({{"pos", l.pos},
                              {"radius", l.radius},
                              {"color", l.color},
                              {"intensity", l.intensity},
                              {"height", l.height}});
        json floor = {{"name", floor_name}, {"tiles", json::array()}, {"lights", lights}};
        if (in.sun)
            floor["sun"] = {{"azimuth", in.sun->azimuth},
                            {"elevation", in.sun->elevation},
                            {"color", in.sun->color},
                            {"intensity", in.sun->intensity}};
        if (f < layout.floor_effects.size() && !layout.floor_effects[f].empty())
            floor["effects"] = effects_json(layout.floor_effects[f]);
        if (!in.tiled) {
            floors.push_back(floor);
            continue;
        }
        const auto image = directory / fmt::format("{}.floor{}.exr", name, f);
        ACETATE_TRY(save_image(image, in.image));
        json tile = {{"image", image.string()}, {"rect", {in.x, in.y, in.width, in.height}}};
        if (!in.masks.empty()) {
            json masks = json::object();
            for (const auto& [kind, mask] : in.masks) {
                const auto file = directory / fmt::format("{}.floor{}.{}.exr", name, f, kind);
                ACETATE_TRY(save_image(file, mask));
                masks[kind] = file.string();
            }
            tile["masks"] = masks;
        }
        floor["tiles"].push_back(tile);
        floors.push_back(floor);
    }
    json scene = {{"format", "acetate-scene/1"},
                  {"canvas",
                   {{"width", layout.width},
                    {"height", layout.height},
                    {"background", {0.0, 0.0, 0.0, 0.0}}}},
                  {"floors", floors}};
    if (!layout.global_effects.empty())
        scene["global_effects"] = effects_json(layout.global_effects);
    // Written beside its images, so the case can be rendered again by hand with `acetate
    // render`; parsed from the same text, so what runs is exactly what the file says.
    const auto file = directory / (name + ".json");
    const std::string text = scene.dump(2) + "\n";
    ACETATE_TRY(write_file_atomically(file, text));
    return parse_scene_text(text, file);
}

}  // namespace acetate::harness
