// Image I/O: the colour conventions (docs/conventions.md, "Colour") on load and save, safe
// un-premultiplication for PNG, half precision for EXR, and atomic writes.

#include "scene/image_io.hpp"

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <vector>

#include "core/atomic_file.hpp"
#include "test_files.hpp"

namespace acetate {
namespace {

namespace fs = std::filesystem;

// IEC 61966-2-1, written out here in double so the tests do not trust the code under test.
double reference_decode(double encoded) {
    return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}
double reference_encode(double linear) {
    return linear <= 0.0031308 ? linear * 12.92 : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

// Writes 8-bit values exactly as given, straight alpha (OpenImageIO would otherwise treat
// them as premultiplied and divide by alpha).
fs::path write_png8(const fs::path& file, int width, int height, int channels,
                    const std::vector<uint8_t>& values) {
    auto out = OIIO::ImageOutput::create(file.string());
    OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:UnassociatedAlpha", 1);
    if (!out || !out->open(file.string(), spec) ||
        !out->write_image(OIIO::TypeDesc::UINT8, values.data()) || !out->close())
        throw std::runtime_error("cannot write " + file.string());
    return file;
}

std::vector<fs::path> files_in(const fs::path& dir) {
    std::vector<fs::path> names;
    for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename());
    std::sort(names.begin(), names.end());
    return names;
}

// A float's precision after one round trip through sRGB decode: float pow, not exact.
constexpr float kFloatTol = 2e-6f;

TEST(ImageIoTest, SrgbCurveIsThePiecewiseIecCurve) {
    EXPECT_EQ(srgb_to_linear(0.0f), 0.0f);
    EXPECT_NEAR(srgb_to_linear(1.0f), 1.0f, kFloatTol);
    EXPECT_FLOAT_EQ(srgb_to_linear(0.04f), 0.04f / 12.92f);  // linear segment
    EXPECT_NEAR(srgb_to_linear(0.5f), 0.21404114, kFloatTol);
    EXPECT_FLOAT_EQ(linear_to_srgb(0.003f), 0.003f * 12.92f);
    for (int i = 0; i <= 255; ++i) {
        const float encoded = float(i) / 255.0f;
        EXPECT_NEAR(srgb_to_linear(encoded), reference_decode(encoded), kFloatTol) << i;
        EXPECT_NEAR(linear_to_srgb(srgb_to_linear(encoded)), encoded, kFloatTol) << i;
    }
}

TEST(ImageIoTest, Png8StraightAlphaIsDecodedThenPremultiplied) {
    const fs::path file = write_png8(test::scratch_dir() / "tile.png", 3, 1, 4,
                                     {255, 128, 64, 128,   // half covered
                                      200, 100, 50, 255,   // opaque
                                      255, 255, 255, 0});  // transparent, colour left behind
    auto loaded = load_image(file, ImageRole::Colour);
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    ASSERT_EQ(loaded->width, 3u);
    ASSERT_EQ(loaded->height, 1u);

    const float* half = loaded->at(0, 0);
    const double alpha = 128.0 / 255.0;
    EXPECT_NEAR(half[0], 1.0 * alpha, kFloatTol);
    // sRGB 128 is linear 0.2158605, sRGB 64 is 0.0512695 (published table values).
    EXPECT_NEAR(half[1], 0.21586050 * alpha, kFloatTol);
    EXPECT_NEAR(half[2], 0.05126946 * alpha, kFloatTol);
    EXPECT_NEAR(half[3], alpha, 1e-7);

    const float* opaque = loaded->at(1, 0);
    EXPECT_NEAR(opaque[0], reference_decode(200 / 255.0), kFloatTol);
    EXPECT_NEAR(opaque[1], reference_decode(100 / 255.0), kFloatTol);
    EXPECT_NEAR(opaque[2], reference_decode(50 / 255.0), kFloatTol);
    EXPECT_EQ(opaque[3], 1.0f);

    const float* clear = loaded->at(2, 0);
    for (int c = 0; c < 4; ++c) EXPECT_EQ(clear[c], 0.0f) << "channel " << c;
}

TEST(ImageIoTest, GreyAndRgbImagesGetTheirMissingChannels) {
    const fs::path dir = test::scratch_dir();
    auto grey = load_image(write_png8(dir / "grey.png", 1, 1, 1, {128}), ImageRole::Colour);
    ASSERT_TRUE(grey.ok()) << grey.error().message;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(grey->at(0, 0)[c], 0.21586050, kFloatTol);
    EXPECT_EQ(grey->at(0, 0)[3], 1.0f);

    auto grey_alpha = load_image(write_png8(dir / "ga.png", 1, 1, 2, {128, 51}), ImageRole::Colour);
    ASSERT_TRUE(grey_alpha.ok()) << grey_alpha.error().message;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(grey_alpha->at(0, 0)[c], 0.21586050 * 0.2, kFloatTol);
    EXPECT_NEAR(grey_alpha->at(0, 0)[3], 0.2, 1e-7);

    auto rgb = load_image(write_png8(dir / "rgb.png", 1, 1, 3, {0, 128, 255}), ImageRole::Colour);
    ASSERT_TRUE(rgb.ok()) << rgb.error().message;
    EXPECT_EQ(rgb->at(0, 0)[0], 0.0f);
    EXPECT_NEAR(rgb->at(0, 0)[1], 0.21586050, kFloatTol);
    EXPECT_NEAR(rgb->at(0, 0)[2], 1.0, kFloatTol);
    EXPECT_EQ(rgb->at(0, 0)[3], 1.0f);
}

TEST(ImageIoTest, MasksAreDataNotDecodedNorPremultiplied) {
    const fs::path file =
        write_png8(test::scratch_dir() / "ground_Water.png", 1, 1, 4, {128, 64, 255, 128});
    auto mask = load_image(file, ImageRole::Mask);
    ASSERT_TRUE(mask.ok()) << mask.error().message;
    EXPECT_NEAR(mask->at(0, 0)[0], 128 / 255.0, 1e-7);
    EXPECT_NEAR(mask->at(0, 0)[1], 64 / 255.0, 1e-7);
    EXPECT_NEAR(mask->at(0, 0)[2], 1.0, 1e-7);
    EXPECT_NEAR(mask->at(0, 0)[3], 128 / 255.0, 1e-7);
}

TEST(ImageIoTest, ExrIsAssociatedAlphaTakenAsIs) {
    ImageRGBA image(3, 1);
    const float values[12] = {0.3f,  0.2f, 0.1f, 0.5f,  // half covered, premultiplied
                              0.25f, 0.5f, 2.0f, 1.0f,  // HDR, opaque
                              0.0f,  0.0f, 0.0f, 0.0f};
    std::copy(values, values + 12, image.pixels.begin());
    const fs::path file = test::write_exr(test::scratch_dir() / "tile.exr", image);
    for (ImageRole role : {ImageRole::Colour, ImageRole::Mask}) {
        auto loaded = load_image(file, role);
        ASSERT_TRUE(loaded.ok()) << loaded.error().message;
        EXPECT_EQ(loaded->pixels, image.pixels) << "float EXR must come back bit-exact";
    }
}

TEST(ImageIoTest, FloatTiffWithStraightAlphaIsPremultipliedNotDecoded) {
    const fs::path file = test::scratch_dir() / "straight.tif";
    auto out = OIIO::ImageOutput::create(file.string());
    OIIO::ImageSpec spec(1, 1, 4, OIIO::TypeDesc::FLOAT);
    spec.attribute("oiio:UnassociatedAlpha", 1);
    const float straight[4] = {0.8f, 0.4f, 0.2f, 0.5f};
    ASSERT_TRUE(out && out->open(file.string(), spec) &&
                out->write_image(OIIO::TypeDesc::FLOAT, straight) && out->close());
    auto loaded = load_image(file, ImageRole::Colour);
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    EXPECT_FLOAT_EQ(loaded->at(0, 0)[0], 0.4f);
    EXPECT_FLOAT_EQ(loaded->at(0, 0)[1], 0.2f);
    EXPECT_FLOAT_EQ(loaded->at(0, 0)[2], 0.1f);
    EXPECT_FLOAT_EQ(loaded->at(0, 0)[3], 0.5f);
}

TEST(ImageIoTest, NonFiniteExrIsRejected) {
    ImageRGBA image(2, 1);
    image.at(1, 0)[2] = std::numeric_limits<float>::quiet_NaN();
    const fs::path file = test::write_exr(test::scratch_dir() / "nan.exr", image);
    auto loaded = load_image(file, ImageRole::Colour);
    ASSERT_FALSE(loaded.ok());
    EXPECT_EQ(loaded.error().code, ErrorCode::ImageDecode);
    EXPECT_EQ(loaded.error().message.rfind(file.string() + ": pixel (1, 0) channel 2 is ", 0), 0u)
        << loaded.error().message;
}

TEST(ImageIoTest, LoadErrorsNameTheFile) {
    const fs::path dir = test::scratch_dir();
    auto missing = load_image(dir / "missing.png", ImageRole::Colour);
    ASSERT_FALSE(missing.ok());
    EXPECT_EQ(missing.error().code, ErrorCode::FileNotFound);
    EXPECT_EQ(missing.error().message, (dir / "missing.png").string() + ": file not found");

    const fs::path garbage = test::write_text(dir / "garbage.png", "this is not a png");
    auto bad = load_image(garbage, ImageRole::Colour);
    ASSERT_FALSE(bad.ok());
    EXPECT_EQ(bad.error().code, ErrorCode::ImageDecode);
    EXPECT_EQ(bad.error().message.rfind(garbage.string() + ": ", 0), 0u) << bad.error().message;
    EXPECT_EQ(bad.error().message.find('\n'), std::string::npos);
}

TEST(ImageIoTest, UnpremultiplyForPngIsSafeAtTinyAlpha) {
    struct Case {
        float in[4];
        uint8_t expected[4];
    };
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    const Case cases[] = {
        {{0.5f / 65535, 0.5f / 65535, 0.0f, 1.0f / 65535}, {0, 0, 0, 0}},
        {{1.0f, 1.0f, 1.0f, 1.0f / 1000}, {0, 0, 0, 0}},  // rgb > a: invalid, still no blow-up
        {{0.0f, 0.0f, 0.0f, 0.0f}, {0, 0, 0, 0}},
        {{0.003f, 0.003f, 0.0f, 0.003f}, {255, 255, 0, 1}},  // alpha rounds to 1/255
        {{nan, inf, 0.25f, 0.5f}, {0, 255, 188, 128}},       // 0.5 straight -> sRGB 188
        {{0.5f, 0.5f, 0.5f, nan}, {0, 0, 0, 0}},
        {{2.0f, -1.0f, 0.5f, 1.0f}, {255, 0, 188, 255}},
    };
    for (const Case& c : cases) {
        uint8_t out[4] = {9, 9, 9, 9};
        premultiplied_to_srgb8(c.in, out);
        for (int k = 0; k < 4; ++k)
            EXPECT_EQ(int(out[k]), int(c.expected[k]))
                << "input (" << c.in[0] << ", " << c.in[1] << ", " << c.in[2] << ", " << c.in[3]
                << ") channel " << k;
    }
}

TEST(ImageIoTest, PngRoundTripMatchesEightBitQuantisation) {
    ImageRGBA image(4, 1);
    const float values[16] = {0.4f,  0.2f,         0.05f,  0.5f,  // premultiplied, half covered
                              0.9f,  0.5f,         0.1f,   1.0f,   1e-5f, 1e-5f,
                              1e-5f, 1.0f / 65535, 0.001f, 0.002f, 0.0f,  0.004f};
    std::copy(values, values + 16, image.pixels.begin());
    const fs::path file = test::scratch_dir() / "out.png";
    auto saved = save_image(file, image);
    ASSERT_TRUE(saved.ok()) << saved.error().message;
    auto loaded = load_image(file, ImageRole::Colour);
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;

    for (uint32_t x = 0; x < 4; ++x) {
        const float* in = image.at(x, 0);
        const float* out = loaded->at(x, 0);
        // What an ideal 8-bit straight-alpha sRGB file holds, decoded again.
        const double alpha8 = std::round(in[3] * 255.0) / 255.0;
        EXPECT_NEAR(out[3], alpha8, 1e-7) << "pixel " << x;
        for (int c = 0; c < 3; ++c) {
            const double straight = alpha8 == 0 ? 0 : std::min(1.0, double(in[c]) / in[3]);
            const double encoded = std::round(reference_encode(straight) * 255.0) / 255.0;
            const double expected = reference_decode(encoded) * alpha8;
            EXPECT_TRUE(std::isfinite(out[c]));
            EXPECT_NEAR(out[c], expected, 1e-5) << "pixel " << x << " channel " << c;
            EXPECT_LE(out[c], out[3] + 1e-6) << "premultiplied invariant, pixel " << x;
        }
    }
}

TEST(ImageIoTest, ExrRoundTripKeepsHalfPrecision) {
    ImageRGBA image(3, 2);
    const float values[24] = {0.1f,  0.333333f, 0.7f,    1.0f,  1.5f,     1000.0f,  0.001f, 0.5f,
                              0.25f, 0.125f,    0.0625f, 0.25f, 3.14159f, 2.71828f, 0.577f, 1.0f,
                              0.0f,  0.0f,      0.0f,    0.0f,  1e-3f,    2e-3f,    3e-3f,  0.9f};
    std::copy(values, values + 24, image.pixels.begin());
    const fs::path file = test::scratch_dir() / "out.exr";
    auto saved = save_image(file, image);
    ASSERT_TRUE(saved.ok()) << saved.error().message;

    auto input = OIIO::ImageInput::open(file.string());
    ASSERT_TRUE(input);
    EXPECT_EQ(input->spec().format, OIIO::TypeDesc::HALF) << "EXR output is half-float";
    input->close();

    auto loaded = load_image(file, ImageRole::Colour);
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    // Half has 11 significant bits; rounding to nearest errs by at most 2^-11 relative for
    // these normal-range values. Premultiplied values come back as is, not divided by alpha.
    const double rel = std::ldexp(1.0, -11);
    for (size_t i = 0; i < image.pixels.size(); ++i)
        EXPECT_NEAR(loaded->pixels[i], image.pixels[i], std::abs(image.pixels[i]) * rel) << i;
}

TEST(ImageIoTest, ExrClampsBeyondHalfRangeInsteadOfWritingInf) {
    ImageRGBA image(1, 1);
    image.pixels = {1e6f, 1.0f, 1.0f, 1.0f};
    const fs::path file = test::scratch_dir() / "bright.exr";
    ASSERT_TRUE(save_image(file, image).ok());
    auto loaded = load_image(file, ImageRole::Colour);
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    EXPECT_EQ(loaded->pixels[0], 65504.0f);
}

TEST(ImageIoTest, SavingLeavesNoTemporaryFiles) {
    const fs::path dir = test::scratch_dir();
    ImageRGBA image(2, 2);
    for (int round = 0; round < 2; ++round) {  // the second round replaces existing files
        ASSERT_TRUE(save_image(dir / "frame.png", image).ok());
        ASSERT_TRUE(save_image(dir / "frame.exr", image).ok());
        ASSERT_TRUE(write_file_atomically(dir / "cache.bin", "bytes").ok());
    }
    EXPECT_EQ(files_in(dir), (std::vector<fs::path>{"cache.bin", "frame.exr", "frame.png"}));
}

TEST(ImageIoTest, AtomicWriteReplacesContent) {
    const fs::path file = test::scratch_dir() / "data.bin";
    ASSERT_TRUE(write_file_atomically(file, "first, longer content").ok());
    ASSERT_TRUE(write_file_atomically(file, std::string_view("sec\0nd", 6)).ok());
    EXPECT_EQ(fs::file_size(file), 6u);
}

TEST(ImageIoTest, FailedWritesNameTheFileAndLeaveNothing) {
    const fs::path dir = test::scratch_dir();
    auto atomic = write_file_atomically(dir / "no-such-dir" / "x.bin", "bytes");
    ASSERT_FALSE(atomic.ok());
    EXPECT_EQ(atomic.error().code, ErrorCode::Io);
    EXPECT_EQ(atomic.error().message.rfind((dir / "no-such-dir" / "x.bin").string() + ": ", 0), 0u)
        << atomic.error().message;

    // The image is encoded in memory; what fails is writing it, and the line says why.
    auto image = save_image(dir / "no-such-dir" / "x.png", ImageRGBA(1, 1));
    ASSERT_FALSE(image.ok());
    EXPECT_EQ(image.error().code, ErrorCode::Io);
    EXPECT_EQ(image.error().message.rfind((dir / "no-such-dir" / "x.png").string() + ": ", 0), 0u)
        << image.error().message;
    EXPECT_NE(image.error().message.find("No such file or directory"), std::string::npos)
        << image.error().message;
    EXPECT_TRUE(files_in(dir).empty());
}

// An image no encoder can squeeze: every byte random, so the file is about as big as the data.
ImageRGBA incompressible(uint32_t side) {
    ImageRGBA image(side, side);
    uint32_t state = 12345;
    for (float& v : image.pixels) {
        state = state * 1664525u + 1013904223u;
        v = float(state >> 8) / float(1u << 24);
    }
    for (size_t i = 3; i < image.pixels.size(); i += 4) image.pixels[i] = 1.0f;
    return image;
}

// A full disk: the write fails with one line naming the file and the cause, the good file that
// was there stays as it was, and no temporary is left. Needs a small tmpfs, so root.
TEST(ImageIoTest, FullDiskKeepsTheOldFileForBothFormats) {
    if (::geteuid() != 0) GTEST_SKIP() << "mounting a small tmpfs needs root";
    const fs::path dir = test::scratch_dir() / "full";
    fs::create_directories(dir);
    ASSERT_EQ(std::system(("mount -t tmpfs -o size=256k tmpfs " + dir.string()).c_str()), 0)
        << "cannot mount a tmpfs on " << dir;
    struct Unmount {
        fs::path dir;
        ~Unmount() { (void)std::system(("umount -l " + dir.string()).c_str()); }
    } unmount{dir};
    for (const char* name : {"frame.png", "frame.exr"}) {
        const fs::path file = dir / name;
        ASSERT_TRUE(save_image(file, ImageRGBA(2, 2)).ok());
        const std::string before = test::read_file(file);
        ASSERT_FALSE(before.empty());
        auto saved = save_image(file, incompressible(512));  // over 768 KiB encoded, 256 KiB disk
        ASSERT_FALSE(saved.ok()) << name << " was written to a disk too small for it";
        EXPECT_EQ(saved.error().code, ErrorCode::Io);
        EXPECT_EQ(saved.error().message.rfind(file.string() + ": ", 0), 0u)
            << saved.error().message;
        EXPECT_NE(saved.error().message.find("No space left on device"), std::string::npos)
            << saved.error().message;
        EXPECT_EQ(saved.error().message.find('\n'), std::string::npos) << saved.error().message;
        EXPECT_EQ(test::read_file(file), before) << name << " lost its old content";
    }
    EXPECT_EQ(files_in(dir), (std::vector<fs::path>{"frame.exr", "frame.png"}));
}

// SIGKILL in the middle of a write leaves no temporary: the data goes to an unnamed file until
// it is complete.
TEST(ImageIoTest, KilledWriterLeavesNoTemporary) {
    const fs::path dir = test::scratch_dir();
    const std::string big(256u << 20, 'x');  // long enough to be mid-write when killed
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        (void)write_file_atomically(dir / "big.bin", big);
        ::_exit(0);
    }
    ::usleep(30 * 1000);
    ::kill(child, SIGKILL);
    int status = 0;
    ::waitpid(child, &status, 0);
    for (const fs::path& name : files_in(dir))
        EXPECT_EQ(name.string().find(".tmp-"), std::string::npos) << "left behind: " << name;
}

// A named temporary of a writer that no longer runs (killed where O_TMPFILE is unavailable) is
// removed by the next write of the same file; a live writer's is left alone.
TEST(ImageIoTest, DeadWritersTemporariesAreRemoved) {
    const fs::path dir = test::scratch_dir();
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) ::_exit(0);
    ::waitpid(child, nullptr, 0);  // a pid that no longer exists (until it is reused)
    const fs::path dead = dir / fmt::format("out.tmp-{}-0.png", child);
    const fs::path live = dir / fmt::format("out.tmp-{}-7.png", ::getpid());
    test::write_text(dead, "half");
    test::write_text(live, "in progress");
    remove_dead_writers_temporaries(dir / "out.png");
    EXPECT_FALSE(fs::exists(dead));
    EXPECT_TRUE(fs::exists(live));
}

TEST(ImageIoTest, NonRegularTargetsAreNotReplaced) {
    const fs::path dir = test::scratch_dir();
    fs::create_directory(dir / "folder.png");
    auto saved = save_image(dir / "folder.png", ImageRGBA(1, 1));
    ASSERT_FALSE(saved.ok());
    EXPECT_NE(saved.error().message.find("it is a directory"), std::string::npos)
        << saved.error().message;
    EXPECT_TRUE(fs::is_directory(dir / "folder.png"));
}

TEST(ImageIoTest, OutputExtensionIsExact) {
    const fs::path dir = test::scratch_dir();
    auto saved = save_image(dir / "out.PNG", ImageRGBA(1, 1));
    ASSERT_FALSE(saved.ok());
    EXPECT_EQ(saved.error().code, ErrorCode::InvalidInput);
    EXPECT_TRUE(files_in(dir).empty());
}

TEST(ImageIoTest, TempSiblingKeepsDirectoryAndExtension) {
    const fs::path temp = temp_sibling("/some/dir/out.png");
    EXPECT_EQ(temp.parent_path(), fs::path("/some/dir"));
    EXPECT_EQ(temp.extension(), ".png");
    EXPECT_EQ(temp.filename().string().rfind("out.tmp-" + std::to_string(::getpid()) + "-", 0), 0u)
        << temp;
    EXPECT_NE(temp_sibling("/some/dir/out.png"), temp) << "two writers never share a temporary";
}

TEST(ImageIoTest, UnsupportedExtensionIsRefused) {
    const fs::path dir = test::scratch_dir();
    auto saved = save_image(dir / "out.jpg", ImageRGBA(1, 1));
    ASSERT_FALSE(saved.ok());
    EXPECT_EQ(saved.error().code, ErrorCode::InvalidInput);
    EXPECT_EQ(saved.error().message, (dir / "out.jpg").string() +
                                         ": unsupported output extension \".jpg\" "
                                         "(supported: .exr, .png)");
    EXPECT_TRUE(files_in(dir).empty());
}

}  // namespace
}  // namespace acetate
