// The scaling study's scenes (scaling.hpp): a realistic layered scene at any size. Each floor
// has three partly overlapping tiles (about 60% of the canvas together, with feathered alpha
// edges), four lights and a sun; floors are stacked with small shifts so no two are alike. The
// tile textures are shared by every scene and canvas (so load time does not grow with the
// canvas): they are drawn magnified on large canvases, which costs the same pixels shaded.

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "scaling.hpp"
#include "scene/image_io.hpp"

namespace acetate::bench {
namespace {

namespace fs = std::filesystem;

constexpr int kTiles = 3;
// Each tile's rect as shares of the canvas: x, y, width, height (before the floor's shift).
constexpr std::array<std::array<double, 4>, kTiles> kTileRects = {{
    {0.06, 0.08, 0.46, 0.56},  // A: carries the water
    {0.40, 0.30, 0.46, 0.52},  // B: carries the fire
    {0.18, 0.58, 0.42, 0.36},  // C
}};
// Each tile's base colour (linear).
constexpr std::array<std::array<float, 3>, kTiles> kTileColours = {{
    {0.45f, 0.42f, 0.38f},  // stone
    {0.50f, 0.32f, 0.20f},  // wood
    {0.30f, 0.34f, 0.40f},  // slate
}};

uint32_t hash(uint32_t x, uint32_t y, uint32_t seed) {
    uint32_t h = x * 0x8da6b343u ^ y * 0xd8163841u ^ seed * 0xcb1ab31fu;
    h ^= h >> 15;
    h *= 0x2c1b3c6du;
    h ^= h >> 12;
    h *= 0x297a2d39u;
    h ^= h >> 15;
    return h;
}

float smoothstep(float e0, float e1, float x) {
    const float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

// The floor's shift, as shares of the canvas: a few percent, different on every floor.
std::array<double, 2> floor_shift(uint32_t floor) {
    return {double(int(floor * 37 % 11) - 5) / 100.0, double(int(floor * 53 % 9) - 4) / 100.0};
}

std::array<double, 4> tile_rect(uint32_t width, uint32_t height, uint32_t floor, int tile) {
    const auto shift = floor_shift(floor);
    const auto& r = kTileRects[size_t(tile)];
    return {std::round((r[0] + shift[0]) * width), std::round((r[1] + shift[1]) * height),
            std::max(1.0, std::round(r[2] * width)), std::max(1.0, std::round(r[3] * height))};
}

ImageRGBA tile_image(uint32_t w, uint32_t h, int tile) {
    ImageRGBA image(w, h);
    const float feather = 0.06f;
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const float u = (float(x) + 0.5f) / float(w), v = (float(y) + 0.5f) / float(h);
            const float edge = std::min(std::min(u, 1.0f - u), std::min(v, 1.0f - v));
            const float a = smoothstep(0.0f, feather, edge);
            // Blocks with mortar between them and noise inside: a texture, not a flat colour.
            const bool mortar = (x % 32) < 2 || (y % 16) < 2;
            const float noise = float(hash(x, y, uint32_t(tile)) >> 8) / float(1u << 24);
            const float shade = mortar ? 0.35f : 0.75f + 0.5f * noise;
            float* p = image.at(x, y);
            for (int c = 0; c < 3; ++c) p[c] = kTileColours[size_t(tile)][size_t(c)] * shade * a;
            p[3] = a;
        }
    return image;
}

ImageRGBA mask_image(uint32_t w, uint32_t h, const std::string& kind) {
    ImageRGBA image(w, h);
    // Three small fire spots, as shares of the tile: x, y, radius (of the width).
    static constexpr std::array<std::array<float, 3>, 3> kFires = {
        {{0.25f, 0.70f, 0.04f}, {0.55f, 0.40f, 0.035f}, {0.80f, 0.75f, 0.045f}}};
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const float u = (float(x) + 0.5f) / float(w), v = (float(y) + 0.5f) / float(h);
            float value = 0;
            if (kind == "specular") {
                // Glossy stripes over a dull base.
                value = ((x / 8 + y / 16) % 3 == 0) ? 1.0f : 0.2f;
            } else if (kind == "water") {
                // A pool: an ellipse with a soft shore.
                const float dx = (u - 0.5f) / 0.34f, dy = (v - 0.55f) / 0.30f;
                value = smoothstep(1.0f, 0.9f, std::sqrt(dx * dx + dy * dy));
            } else if (kind == "fire") {
                const float aspect = float(h) / float(w);
                for (const auto& f : kFires) {
                    const float dx = u - f[0], dy = (v - f[1]) * aspect;
                    value = std::max(value,
                                     smoothstep(f[2], 0.7f * f[2], std::sqrt(dx * dx + dy * dy)));
                }
            }
            float* p = image.at(x, y);
            p[0] = p[1] = p[2] = value;
            p[3] = 1.0f;
        }
    return image;
}

std::string tile_file(int tile) {
    return fmt::format("tile_{}.exr", char('a' + tile));
}
std::string mask_file(int tile, const std::string& kind) {
    return fmt::format("tile_{}_{}.exr", char('a' + tile), kind);
}

}  // namespace

const std::vector<std::string>& scaling_effect_plugins() {
    static const std::vector<std::string> ids = {"acetate.lighting", "acetate.specular",
                                                 "acetate.water", "acetate.fire",
                                                 "acetate.lighting"};
    return ids;
}

Result<void> write_scaling_assets(const fs::path& dir, uint32_t texture_width) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    const uint32_t w = std::max(8u, texture_width), h = std::max(6u, texture_width * 3 / 4);
    for (int t = 0; t < kTiles; ++t) {
        if (auto saved = save_image(dir / tile_file(t), tile_image(w, h, t)); !saved)
            return saved.error();
        std::vector<std::string> kinds = {"specular"};
        if (t == 0) kinds.push_back("water");
        if (t == 1) kinds.push_back("fire");
        for (const std::string& kind : kinds)
            if (auto saved = save_image(dir / mask_file(t, kind), mask_image(w / 2, h / 2, kind));
                !saved)
                return saved.error();
    }
    return {};
}

Result<fs::path> write_scaling_scene(const fs::path& dir, const std::string& name, uint32_t width,
                                     uint32_t height, uint32_t floors, uint32_t effects_per_floor) {
    using nlohmann::json;
    const auto& plugins = scaling_effect_plugins();
    if (effects_per_floor > plugins.size())
        return make_error(ErrorCode::InvalidInput,
                          fmt::format("--scaling: at most {} effects per floor, asked for {}",
                                      plugins.size(), effects_per_floor));
    const double w = width, h = height, reach = std::max(w, h);
    json scene_floors = json::array();
    for (uint32_t f = 0; f < floors; ++f) {
        json tiles = json::array();
        for (int t = 0; t < kTiles; ++t) {
            const auto r = tile_rect(width, height, f, t);
            json masks = {{"specular", mask_file(t, "specular")}};
            if (t == 0) masks["water"] = mask_file(t, "water");
            if (t == 1) masks["fire"] = mask_file(t, "fire");
            tiles.push_back(
                {{"image", tile_file(t)}, {"rect", {r[0], r[1], r[2], r[3]}}, {"masks", masks}});
        }
        // Four lights spread over the floor's tiles, warm and cool, raised a little.
        const auto shift = floor_shift(f);
        static constexpr std::array<std::array<double, 2>, 4> kLights = {
            {{0.25, 0.30}, {0.65, 0.45}, {0.35, 0.75}, {0.75, 0.70}}};
        json lights = json::array();
        for (size_t i = 0; i < kLights.size(); ++i) {
            const bool warm = i % 2 == 0;
            lights.push_back(
                {{"pos", {(kLights[i][0] + shift[0]) * w, (kLights[i][1] + shift[1]) * h}},
                 {"radius", 0.3 * reach},
                 {"color", warm ? json{1.0, 0.8, 0.6} : json{0.6, 0.8, 1.0}},
                 {"intensity", 2.0},
                 {"height", 0.03 * reach}});
        }
        json effects = json::array();
        for (uint32_t e = 0; e < effects_per_floor; ++e) {
            json effect = {{"plugin", plugins[e]}};
            // The second lighting: a brighter day, so it is not the first one again.
            if (e == 4) effect["params"] = {{"day", 0.8}};
            effects.push_back(effect);
        }
        json floor = {{"name", fmt::format("floor{}", f)},
                      {"tiles", tiles},
                      {"lights", lights},
                      {"sun",
                       {{"azimuth", 135},
                        {"elevation", 35},
                        {"color", {1.0, 0.9, 0.7}},
                        {"intensity", 1.5}}}};
        if (!effects.empty()) floor["effects"] = effects;
        scene_floors.push_back(floor);
    }
    const json scene = {
        {"format", "acetate-scene/1"},
        {"canvas", {{"width", width}, {"height", height}, {"background", {0.05, 0.05, 0.06, 1.0}}}},
        {"floors", scene_floors},
        {"active_floor", floors - 1}};
    const fs::path file = dir / name;
    if (auto written = write_file_atomically(file, scene.dump(1) + "\n"); !written)
        return written.error();
    return file;
}

double scaling_floor_coverage(uint32_t width, uint32_t height, uint32_t floor) {
    // The union of the rects, on the pixel grid (a step of at most 1/512 of the canvas).
    const uint32_t step = std::max(1u, std::max(width, height) / 512);
    uint64_t covered = 0, total = 0;
    std::array<std::array<double, 4>, kTiles> rects{};
    for (int t = 0; t < kTiles; ++t) rects[size_t(t)] = tile_rect(width, height, floor, t);
    for (uint32_t y = 0; y < height; y += step)
        for (uint32_t x = 0; x < width; x += step) {
            ++total;
            const double px = x + 0.5, py = y + 0.5;
            for (const auto& r : rects)
                if (px >= r[0] && px < r[0] + r[2] && py >= r[1] && py < r[1] + r[3]) {
                    ++covered;
                    break;
                }
        }
    return total ? double(covered) / double(total) : 0.0;
}

}  // namespace acetate::bench
