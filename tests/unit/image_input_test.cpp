// Image files go through the project's one input reader before a decoder sees them, and a
// decoder's own stderr never breaks the one-line promise.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string_view>

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

// CRC-32 (PNG's chunk checksum), bitwise: enough for the few bytes of a header.
uint32_t crc32(std::string_view bytes) {
    uint32_t crc = 0xffffffffu;
    for (unsigned char byte : bytes) {
        crc ^= byte;
        for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

std::string big_endian(uint32_t v) {
    return {char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
}

std::string png_chunk(const std::string& type, const std::string& data) {
    return big_endian(uint32_t(data.size())) + type + data + big_endian(crc32(type + data));
}

// A 54-byte PNG declaring 10000x10000 pixels (a decompression bomb's header): refused from its
// header, before 3.2 GB would be allocated to decode it.
TEST(ImageInput, AnImageOfTooManyPixelsIsRefusedBeforeDecoding) {
    const fs::path file = test::scratch_dir() / "bomb.png";
    const std::string ihdr =
        big_endian(10000) + big_endian(10000) + std::string("\x08\x06\0\0\0", 5);
    std::ofstream(file, std::ios::binary)
        << std::string("\x89PNG\r\n\x1a\n", 8) + png_chunk("IHDR", ihdr) +
               png_chunk("IDAT", std::string("\x78\x9c", 2)) + png_chunk("IEND", "");
    auto loaded = load_image(file, ImageRole::Colour);
    ASSERT_FALSE(loaded);
    EXPECT_EQ(loaded.error().message,
              file.string() + ": image is 10000x10000, more than 67108864 pixels (8192x8192)");
}

// An EXR header attribute declaring more bytes than the file holds is refused before OpenEXR
// reads it (it would allocate what the attribute declares).
TEST(ImageInput, AnExrAttributeLongerThanTheFileIsRefused) {
    const fs::path file = test::scratch_dir() / "lying.exr";
    std::string bytes("\x76\x2f\x31\x01\x02\0\0\0", 8);
    bytes += std::string("comments\0string\0", 16) + std::string("\xff\xff\xff\x7f", 4) + "abc";
    std::ofstream(file, std::ios::binary) << bytes;
    auto loaded = load_image(file, ImageRole::Colour);
    ASSERT_FALSE(loaded);
    EXPECT_EQ(loaded.error().message, file.string() +
                                          ": EXR header: attribute \"comments\" "
                                          "declares 2147483647 bytes; the file has 3 "
                                          "left");
    // The fuzzer's first find here: a name with a newline in it still makes one line.
    const fs::path odd = test::scratch_dir() / "odd.exr";
    std::ofstream(odd, std::ios::binary) << std::string("\x76\x2f\x31\x01\x02\0\0\0", 8) +
                                                std::string("a\nb\0string\0", 11) +
                                                std::string("\xff\0\0\0", 4);
    auto one_line = load_image(odd, ImageRole::Colour);
    ASSERT_FALSE(one_line);
    EXPECT_EQ(one_line.error().message,
              odd.string() +
                  ": EXR header: attribute \"a\\x0ab\" declares 255 bytes; the file "
                  "has 0 left");
    // A real EXR passes the check and loads.
    const fs::path good = test::scratch_dir() / "good.exr";
    ASSERT_TRUE(save_image(good, ImageRGBA(3, 2)));
    EXPECT_TRUE(load_image(good, ImageRole::Colour));
}

// The image fuzzer's find: a text chunk declaring 1.8 GB in a 239-byte PNG, which libpng
// allocated before reading (6 to 14 s). Refused from the bytes, at once, in one line; a real PNG
// (every chunk fits, up to IEND) still loads.
TEST(ImageInput, APngChunkLongerThanTheFileIsRefused) {
    const fs::path file = test::scratch_dir() / "lying.png";
    std::string bytes("\x89PNG\r\n\x1a\n", 8);
    bytes += std::string("\0\0\0\x0dIHDR\0\0\0\x04\0\0\0\x04\x08\x06\0\0\0\xa9\xf1\x9e\x7e", 25);
    bytes += std::string("\x6f\0\0\x5atEXtabc", 11);
    std::ofstream(file, std::ios::binary) << bytes;
    auto loaded = load_image(file, ImageRole::Colour);
    ASSERT_FALSE(loaded);
    EXPECT_EQ(loaded.error().code, ErrorCode::ImageDecode);
    EXPECT_EQ(loaded.error().message, file.string() +
                                          ": PNG chunk 'tEXt' at byte 33 declares 1862271066 "
                                          "bytes of data, but the file has 3 left after its "
                                          "header");
    const fs::path good = test::scratch_dir() / "good.png";
    ImageRGBA pixels(3, 2);
    pixels.pixels.assign(pixels.pixels.size(), 0.5f);
    ASSERT_TRUE(save_image(good, pixels));
    EXPECT_TRUE(load_image(good, ImageRole::Colour));
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
