// Image files go through the project's one input reader before a decoder sees them, and a
// decoder's own stderr never breaks the one-line promise.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>

#include "core/stderr_capture.hpp"
#include "scene/image_io.hpp"
#include "test_files.hpp"

namespace acetate {
namespace {

namespace fs = std::filesystem;

// A valid PNG cut in half: libpng prints "libpng error: ..." itself before OpenImageIO fails.
TEST(ImageInput, TruncatedPngIsOneLineAndTheLibraryPrintsNothing) {
    const fs::path dir = test::scratch_dir();
    const fs::path whole = dir / "whole.png", cut = dir / "cut.png";
    ImageRGBA image(64, 64);
    for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = float(i % 251) / 251.0f;
    for (size_t i = 3; i < image.pixels.size(); i += 4) image.pixels[i] = 1.0f;
    ASSERT_TRUE(save_image(whole, image));
    const std::string bytes = test::read_file(whole);
    std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);

    StderrCapture printed;
    auto loaded = load_image(cut, ImageRole::Colour);
    const std::string text = printed.finish();
    ASSERT_FALSE(loaded);
    EXPECT_EQ(loaded.error().code, ErrorCode::ImageDecode);
    EXPECT_EQ(loaded.error().message.rfind(cut.string() + ": ", 0), 0u) << loaded.error().message;
    EXPECT_EQ(loaded.error().message.find('\n'), std::string::npos);
    EXPECT_EQ(text, "") << "a decoder printed on stderr";
}

TEST(ImageInput, AFifoIsRefusedWithoutWaitingForAWriter) {
    const fs::path fifo = test::scratch_dir() / "tile.png";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    auto loaded = load_image(fifo, ImageRole::Colour);
    ASSERT_FALSE(loaded);
    EXPECT_EQ(loaded.error().message, fifo.string() + ": not a regular file (a FIFO)");
}

TEST(ImageInput, StderrCaptureHoldsWhatWasPrintedAndRestoresTheStream) {
    StderrCapture outer;
    {
        StderrCapture inner;
        std::fprintf(stderr, "from a library\n");
        EXPECT_EQ(inner.finish(), "from a library\n");
    }
    std::fprintf(stderr, "after\n");
    EXPECT_EQ(outer.finish(), "after\n");
}

}  // namespace
}  // namespace acetate
