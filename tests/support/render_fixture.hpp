#pragma once
// Shared set-up for the GPU suites: one Vulkan context per process with validation layers on,
// scenes built from in-memory images, and a TearDown that fails the test on any validation
// message the test caused.

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "render/compositor.hpp"
#include "render/renderer.hpp"
#include "scene/image_io.hpp"
#include "scene/scene.hpp"
#include "vulkan/vulkan_context.hpp"

namespace acetate::test {

class RenderTest : public ::testing::Test {
  protected:
    void SetUp() override;
    void TearDown() override;

    static VulkanContext& context();
    // Process-wide, like the CLI's: plugins from the build tree and the test plugins.
    static Renderer& renderer();
    // This test's scratch folder (created fresh in SetUp).
    const std::filesystem::path& dir() const { return dir_; }

    // A scene of width x height with a background, written into this test's scratch folder.
    SceneDesc make_scene(uint32_t width, uint32_t height,
                         std::array<float, 4> background = {0, 0, 0, 0});
    // Adds a floor and returns its index.
    uint32_t add_floor(SceneDesc& scene, const std::string& name);
    // Adds a tile drawn from `image` (saved as float EXR: associated alpha, exact) at `rect`.
    void add_tile(SceneDesc& scene, uint32_t floor, const ImageRGBA& image, SceneRect rect);

    std::unique_ptr<Compositor> load(const SceneDesc& scene, CompositorOptions options = {});
    // Renders `floor` and returns the output image; fails the test on error.
    ImageRGBA render(Compositor& compositor, uint32_t floor, FrameStats* stats = nullptr);

  private:
    size_t messages_before_ = 0;
    std::filesystem::path dir_;
    int files_ = 0;
};

// An image filled with one premultiplied colour.
ImageRGBA solid(uint32_t width, uint32_t height, std::array<float, 4> rgba);

// Largest absolute difference over all channels; images must be the same size.
double max_abs_difference(const ImageRGBA& a, const ImageRGBA& b);

// Writes actual and expected as EXR beside the test's scratch folder, for a person to look at
// when a comparison fails; returns where.
std::string save_failure_images(const std::string& name, const ImageRGBA& actual,
                                const ImageRGBA& expected);

}  // namespace acetate::test
