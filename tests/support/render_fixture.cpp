#include "render_fixture.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>

#include "test_files.hpp"

namespace acetate::test {

VulkanContext& RenderTest::context() {
    static std::unique_ptr<VulkanContext> shared = [] {
        ContextOptions options = ContextOptions::from_environment();
        options.validation = true;  // always on in the test suite
        auto created = VulkanContext::create(options);
        if (!created) {
            std::fprintf(stderr, "cannot create a Vulkan context: %s\n",
                         created.error().message.c_str());
            std::abort();
        }
        return std::move(created.value());
    }();
    return *shared;
}

Renderer& RenderTest::renderer() {
    static std::unique_ptr<Renderer> shared = [] {
        RendererOptions options;
#ifdef ACETATE_PLUGIN_DIR
        options.plugin_directories.push_back(ACETATE_PLUGIN_DIR);
#endif
#ifdef ACETATE_TEST_PLUGIN_DIR
        options.plugin_directories.push_back(ACETATE_TEST_PLUGIN_DIR);
#endif
        auto created = Renderer::create(context(), options);
        if (!created) {
            std::fprintf(stderr, "cannot create the renderer: %s\n",
                         created.error().message.c_str());
            std::abort();
        }
        return std::move(created.value());
    }();
    return *shared;
}

void RenderTest::SetUp() {
    messages_before_ = context().validation_messages().size();
    dir_ = scratch_dir();
}

void RenderTest::TearDown() {
    const auto& messages = context().validation_messages();
    EXPECT_EQ(messages.size(), messages_before_)
        << "Vulkan validation messages during this test; first: "
        << (messages.size() > messages_before_ ? messages[messages_before_] : "");
}

SceneDesc RenderTest::make_scene(uint32_t width, uint32_t height, std::array<float, 4> background) {
    SceneDesc scene;
    scene.file = dir_ / "scene.json";
    scene.width = width;
    scene.height = height;
    scene.background = background;
    return scene;
}

uint32_t RenderTest::add_floor(SceneDesc& scene, const std::string& name) {
    FloorDesc floor;
    floor.name = name;
    scene.floors.push_back(floor);
    scene.active_floor = uint32_t(scene.floors.size() - 1);
    return scene.active_floor;
}

void RenderTest::add_tile(SceneDesc& scene, uint32_t floor, const ImageRGBA& image,
                          SceneRect rect) {
    TileDesc tile;
    tile.image = write_exr(dir_ / fmt::format("tile{}.exr", files_++), image);
    tile.rect = rect;
    scene.floors.at(floor).tiles.push_back(tile);
}

std::unique_ptr<Compositor> RenderTest::load(const SceneDesc& scene, CompositorOptions options) {
    auto loaded = Compositor::load(renderer(), scene, options);
    if (!loaded) {
        ADD_FAILURE() << "load failed: " << loaded.error().message;
        return nullptr;
    }
    return std::move(loaded.value());
}

ImageRGBA RenderTest::render(Compositor& compositor, uint32_t floor, FrameStats* stats) {
    auto frame = compositor.render(floor);
    if (!frame) {
        ADD_FAILURE() << "render failed: " << frame.error().message;
        return {};
    }
    if (stats) *stats = frame.value();
    auto output = compositor.read_output();
    if (!output) {
        ADD_FAILURE() << "read back failed: " << output.error().message;
        return {};
    }
    return std::move(output.value());
}

ImageRGBA solid(uint32_t width, uint32_t height, std::array<float, 4> rgba) {
    ImageRGBA image(width, height);
    for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = rgba[i % 4];
    return image;
}

double max_abs_difference(const ImageRGBA& a, const ImageRGBA& b) {
    if (a.width != b.width || a.height != b.height) return INFINITY;
    double worst = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i)
        worst = std::max(worst, std::fabs(double(a.pixels[i]) - double(b.pixels[i])));
    return worst;
}

std::string save_failure_images(const std::string& name, const ImageRGBA& actual,
                                const ImageRGBA& expected) {
    const auto dir = std::filesystem::temp_directory_path() / "acetate-test-failures";
    std::filesystem::create_directories(dir);
    const auto a = dir / (name + ".actual.exr");
    const auto e = dir / (name + ".expected.exr");
    write_exr(a, actual);
    write_exr(e, expected);
    ImageRGBA diff(actual.width, actual.height);
    for (size_t i = 0; i < diff.pixels.size() && i < expected.pixels.size(); ++i)
        diff.pixels[i] = std::fabs(actual.pixels[i] - expected.pixels[i]);
    write_exr(dir / (name + ".diff.exr"), diff);
    return dir.string();
}

}  // namespace acetate::test
