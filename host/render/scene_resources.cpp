#include "render/scene_resources.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdio>

#include "scene/image_io.hpp"
#include "vulkan/vulkan_context.hpp"

namespace acetate {
namespace {

uint64_t count_violations(const ImageRGBA& image) {
    uint64_t count = 0;
    for (size_t i = 0; i < image.pixels.size(); i += 4) {
        const float* p = &image.pixels[i];
        const bool finite = std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]) &&
                            std::isfinite(p[3]);
        if (!finite || (p[3] <= 0.0f && (p[0] != 0.0f || p[1] != 0.0f || p[2] != 0.0f))) ++count;
    }
    return count;
}

// Texels a premultiplied colour cannot hold but a float file can: a negative channel, or alpha
// above 1. They are drawn as stored (the tile stage does not clamp), so a person is told once.
uint64_t count_out_of_range(const ImageRGBA& image) {
    uint64_t count = 0;
    for (size_t i = 0; i < image.pixels.size(); i += 4) {
        const float* p = &image.pixels[i];
        if (p[0] < 0.0f || p[1] < 0.0f || p[2] < 0.0f || p[3] < 0.0f || p[3] > 1.0f) ++count;
    }
    return count;
}

bool fully_opaque(const ImageRGBA& image) {
    for (size_t i = 3; i < image.pixels.size(); i += 4)
        if (image.pixels[i] != 1.0f) return false;
    return true;
}

Result<std::unique_ptr<GpuImage>> upload(VulkanContext& context, const std::string& name,
                                         const ImageRGBA& pixels, VkFormat format) {
    auto image =
        GpuImage::create(context, name, pixels.width, pixels.height, format,
                         VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, false);
    if (!image) return image.error();
    auto owned = std::make_unique<GpuImage>(std::move(image.value()));
    ACETATE_TRY(upload_image(context, *owned, pixels));
    return owned;
}

}  // namespace

Result<std::unique_ptr<SceneResources>> SceneResources::load(
    VulkanContext& context, const SceneDesc& scene, VkFormat texture_format,
    const std::set<std::string>& mask_kinds, const SceneMasks& masks) {
    auto out = std::make_unique<SceneResources>();
    struct Texture {
        const GpuImage* image;
        bool opaque;
        uint32_t width, height;
    };
    std::map<std::filesystem::path, Texture> by_path;  // a file shared by tiles loads once

    // Errors name the scene field that refers to the file, not only the file.
    auto in_scene = [&](const Error& e, size_t f, size_t t, const std::string& field) {
        return make_error(e.code, fmt::format("{}: floors[{}].tiles[{}].{}: {}",
                                              scene.file.string(), f, t, field, e.message));
    };
    for (size_t f = 0; f < scene.floors.size(); ++f) {
        const FloorDesc& floor_desc = scene.floors[f];
        LoadedFloor floor;
        floor.name = floor_desc.name;
        for (size_t t = 0; t < floor_desc.tiles.size(); ++t) {
            const TileDesc& tile = floor_desc.tiles[t];
            auto found = by_path.find(tile.image);
            if (found == by_path.end()) {
                auto pixels = load_image(tile.image, ImageRole::Colour);
                if (!pixels) return in_scene(pixels.error(), f, t, "image");
                ++context.counters().images_loaded;
                auto texture = upload(context, "tile " + tile.image.filename().string(),
                                      pixels.value(), texture_format);
                if (!texture) return in_scene(texture.error(), f, t, "image");
                out->tile_texel_violations_ += count_violations(pixels.value());
                if (const uint64_t odd = count_out_of_range(pixels.value()))
                    std::fprintf(stderr,
                                 "acetate: warning: %s: floors[%zu].tiles[%zu].image: %llu "
                                 "texels have a negative channel or alpha above 1 (premultiplied "
                                 "colour needs 0 <= rgb and 0 <= a <= 1); drawn as stored\n",
                                 scene.file.c_str(), f, t, static_cast<unsigned long long>(odd));
                found = by_path
                            .emplace(tile.image,
                                     Texture{texture.value().get(), fully_opaque(pixels.value()),
                                             pixels->width, pixels->height})
                            .first;
                out->textures_.push_back(std::move(texture.value()));
            }
            LoadedTile loaded;
            loaded.texture = found->second.image;
            loaded.rect = tile.rect;
            loaded.pixels = pixels_covered(tile.rect.x, tile.rect.y, tile.rect.width,
                                           tile.rect.height, scene.width, scene.height);
            loaded.opaque = found->second.opaque;
            loaded.one_to_one = tile.rect.width == found->second.width &&
                                tile.rect.height == found->second.height &&
                                tile.rect.x == std::floor(tile.rect.x) &&
                                tile.rect.y == std::floor(tile.rect.y);
            floor.geometry.coverage = bounding_union(floor.geometry.coverage, loaded.pixels);
            if (loaded.opaque && !loaded.pixels.empty())
                floor.geometry.opaque.push_back(loaded.pixels);
            floor.tiles.push_back(loaded);
        }
        floor.geometry.needs_target = !floor_desc.effects.empty();
        out->floors_.push_back(std::move(floor));
    }

    // One scene-space texture per kind per floor, only for kinds asked for and present: the
    // composites build() already read, uploaded as they are.
    context.counters().images_loaded += masks.files_decoded;
    for (size_t f = 0; f < scene.floors.size(); ++f) {
        for (const std::string& kind : mask_kinds) {
            const auto composite = masks.floors.at(f).find(kind);
            if (composite == masks.floors.at(f).end()) {
                if (!out->blank_mask_) {
                    auto blank = GpuImage::create(
                        context, "mask.blank", scene.width, scene.height,
                        VK_FORMAT_R16G16B16A16_SFLOAT,
                        VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, false);
                    if (!blank) return blank.error();
                    out->blank_mask_ = std::move(blank.value());
                    ACETATE_TRY(upload_image(context, *out->blank_mask_,
                                             ImageRGBA(scene.width, scene.height)));
                }
                continue;
            }
            auto image = GpuImage::create(
                context, fmt::format("floor{}.mask.{}", f, kind), scene.width, scene.height,
                VK_FORMAT_R16G16B16A16_SFLOAT,
                VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, false);
            if (!image) return image.error();
            ACETATE_TRY(upload_image(context, image.value(), composite->second));
            out->floors_[f].masks.emplace(kind, std::move(image.value()));
        }
    }
    return out;
}

std::vector<const GpuImage*> SceneResources::images() const {
    std::vector<const GpuImage*> out;
    for (const auto& t : textures_) out.push_back(t.get());
    for (const LoadedFloor& f : floors_)
        for (const auto& [kind, image] : f.masks) out.push_back(&image);
    if (blank_mask_) out.push_back(&*blank_mask_);
    return out;
}

}  // namespace acetate
