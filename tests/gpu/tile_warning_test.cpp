// A float tile image may hold what premultiplied colour cannot (a negative channel, alpha above
// 1). It is drawn as stored, and the load says so once, in one line naming the scene field.
#include <gtest/gtest.h>

#include <sstream>

#include "core/stderr_capture.hpp"
#include "render_fixture.hpp"

namespace acetate::test {
namespace {

class TileWarningTest : public RenderTest {
  protected:
    // The lines of stderr a load printed that start with "acetate:".
    std::vector<std::string> load_and_collect(const ImageRGBA& tile) {
        SceneDesc scene = make_scene(8, 8);
        add_tile(scene, add_floor(scene, "ground"), tile, {0, 0, 8, 8});
        StderrCapture printed;
        auto compositor = load(scene);
        std::istringstream lines(printed.finish());
        EXPECT_TRUE(compositor);
        std::vector<std::string> ours;
        for (std::string line; std::getline(lines, line);)
            if (line.rfind("acetate:", 0) == 0) ours.push_back(line);
        return ours;
    }
};

TEST_F(TileWarningTest, NegativeColourAndAlphaAboveOneAreReportedOnce) {
    ImageRGBA tile = solid(8, 8, {0.2f, 0.2f, 0.2f, 1.0f});
    tile.at(1, 1)[0] = -0.5f;                           // a negative channel
    tile.at(2, 2)[3] = 1.5f;                            // alpha above 1
    tile.at(3, 3)[1] = -1.0f, tile.at(3, 3)[3] = 2.0f;  // both: one texel
    const std::vector<std::string> lines = load_and_collect(tile);
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_NE(lines[0].find(": floors[0].tiles[0].image: 3 texels have a negative channel or "
                            "alpha above 1"),
              std::string::npos)
        << lines[0];
}

TEST_F(TileWarningTest, AnOrdinaryTilePrintsNothing) {
    EXPECT_TRUE(load_and_collect(solid(8, 8, {0.1f, 0.2f, 0.3f, 0.5f})).empty());
}

}  // namespace
}  // namespace acetate::test
