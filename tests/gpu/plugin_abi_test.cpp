// ABI negative cases: each broken test plugin is refused with a one-line error naming the
// plugin file (or the scene field and pass), and the host keeps going: the same renderer then
// loads and renders a good scene.

#include "render_fixture.hpp"

namespace acetate::test {
namespace {

struct BrokenCase {
    const char* id;
    std::vector<const char*> message_has;
};

class PluginAbi : public RenderTest, public ::testing::WithParamInterface<BrokenCase> {
  protected:
    SceneDesc scene_with(const std::string& plugin) {
        SceneDesc scene = make_scene(16, 16);
        const uint32_t floor = add_floor(scene, "ground");
        add_tile(scene, floor, solid(16, 16, {0.5f, 0.5f, 0.5f, 1}), {0, 0, 16, 16});
        EffectRef ref;
        ref.plugin = plugin;
        ref.where = "floors[0].effects[0]";
        scene.floors[floor].effects = {ref};
        return scene;
    }
};

TEST_P(PluginAbi, IsRefusedClearlyAndTheHostKeepsGoing) {
    const BrokenCase& c = GetParam();
    auto refused = Compositor::load(renderer(), scene_with(c.id), {});
    ASSERT_FALSE(refused.ok()) << c.id << " was accepted";
    const std::string& message = refused.error().message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
    for (const char* part : c.message_has)
        EXPECT_NE(message.find(part), std::string::npos)
            << "\"" << part << "\" not in: " << message;
    // The host is unharmed: a good plugin on the same renderer still works.
    auto good = load(scene_with("acetate.lighting"));
    ASSERT_TRUE(good);
    FrameStats stats;
    const ImageRGBA out = render(*good, 0, &stats);
    EXPECT_EQ(stats.violations, 0u);
    EXPECT_GT(out.at(8, 8)[0], 0.0f);
}

INSTANTIATE_TEST_SUITE_P(
    Broken, PluginAbi,
    ::testing::Values(
        BrokenCase{"test.no_entry", {"no_entry.so", "no entry point acetate_effect_entry_v1"}},
        BrokenCase{"test.wrong_abi", {"wrong_abi.so", "ABI version 2"}},
        BrokenCase{"test.refuses_abi", {"refuses_abi.so", "cannot serve ABI version 1"}},
        BrokenCase{"test.null_descriptor", {"null_descriptor.so", "no descriptor"}},
        BrokenCase{"test.bad_default", {"bad_default.so", "\"strength\"", "default 1.5", "[0, 1]"}},
        BrokenCase{"test.bad_shader",
                   {"floors[0].effects[0]", "test.bad_shader.broken", "undeclared_thing",
                    "bad_shader.so"}},
        BrokenCase{"test.build_fails",
                   {"floors[0].effects[0]", "build failed", "the floor has no water mask"}},
        BrokenCase{"test.reads_unwritten",
                   {"test.reads_unwritten.combine", "\"blurred\"", "no earlier pass writes"}},
        BrokenCase{"test.not_installed", {"floors[0].effects[0].plugin", "not found"}}),
    [](const ::testing::TestParamInfo<BrokenCase>& info) {
        std::string name = std::string(info.param.id).substr(5);
        return name;
    });

TEST_F(RenderTest, APluginIdThatIsAPathIsRefusedBeforeAnyFileIsOpened) {
    for (const char* id : {"../tests/test-plugins/sparks", "/tmp/evil", "test.sparks/../x"}) {
        auto refused = renderer().plugins().load(id);
        ASSERT_FALSE(refused.ok()) << id;
        EXPECT_NE(refused.error().message.find("not a reverse-DNS name"), std::string::npos)
            << refused.error().message;
    }
}

TEST_F(RenderTest, AFloorEffectListedAsGlobalIsRefused) {
    SceneDesc scene = make_scene(8, 8);
    const uint32_t floor = add_floor(scene, "ground");
    add_tile(scene, floor, solid(8, 8, {0.5f, 0.5f, 0.5f, 1}), {0, 0, 8, 8});
    EffectRef ref;
    ref.plugin = "acetate.lighting";
    ref.where = "global_effects[0]";
    scene.global_effects = {ref};
    auto refused = Compositor::load(renderer(), scene, {});
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().message.find("is a floor effect"), std::string::npos)
        << refused.error().message;
}

TEST_F(RenderTest, ASceneWithoutPluginsLoadsNone) {
    const size_t before = renderer().plugins().loaded_count();
    SceneDesc scene = make_scene(8, 8);
    const uint32_t floor = add_floor(scene, "ground");
    add_tile(scene, floor, solid(8, 8, {0.5f, 0.5f, 0.5f, 1}), {0, 0, 8, 8});
    auto compositor = load(scene);
    ASSERT_TRUE(compositor);
    EXPECT_EQ(renderer().plugins().loaded_count(), before);
    // Nor a floor target or ping-pong partner: tiles draw straight into the accumulation.
    for (const TargetInfo& t : compositor->targets_held())
        EXPECT_EQ(t.name.find("transient"), std::string::npos) << t.name;
}

}  // namespace
}  // namespace acetate::test
