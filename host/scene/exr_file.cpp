#include "scene/exr_file.hpp"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfRgba.h>
#include <ImfRgbaFile.h>

#include <algorithm>
#include <cstring>
#include <exception>
#include <stdexcept>

namespace acetate {
namespace {

// The file's bytes, already read and checked by the host (scene/exr_header_check.hpp), as the
// stream OpenEXR reads from: it never opens a path itself.
class MemoryInput final : public Imf::IStream {
  public:
    MemoryInput(const char* data, size_t size) : Imf::IStream("memory"), data_(data), size_(size) {}
    bool isMemoryMapped() const override { return true; }
    char* readMemoryMapped(int count) override {
        check(count);
        char* at = const_cast<char*>(data_ + position_);
        position_ += size_t(count);
        return at;
    }
    bool read(char out[], int count) override {
        check(count);
        std::memcpy(out, data_ + position_, size_t(count));
        position_ += size_t(count);
        return position_ < size_;
    }
    uint64_t tellg() override { return position_; }
    void seekg(uint64_t position) override {
        position_ = size_t(std::min<uint64_t>(position, size_));
    }

  private:
    void check(int count) const {
        if (count < 0 || size_t(count) > size_ - position_)
            throw std::runtime_error("the file ends early");
    }
    const char* data_;
    size_t size_, position_ = 0;
};

// What OpenEXR writes, in memory (it seeks back to fill in its table of line offsets).
class MemoryOutput final : public Imf::OStream {
  public:
    explicit MemoryOutput(std::vector<unsigned char>& bytes)
        : Imf::OStream("memory"), bytes_(bytes) {}
    void write(const char data[], int count) override {
        if (position_ + size_t(count) > bytes_.size()) bytes_.resize(position_ + size_t(count));
        std::memcpy(bytes_.data() + position_, data, size_t(count));
        position_ += size_t(count);
    }
    uint64_t tellp() override { return position_; }
    void seekp(uint64_t position) override { position_ = size_t(position); }

  private:
    std::vector<unsigned char>& bytes_;
    size_t position_ = 0;
};

constexpr int kNoThreads = 0;  // decode and encode on the calling thread only

// One float slice of a four-float-per-pixel buffer whose first pixel is the data window's
// corner (OpenEXR addresses slices from the file's origin); a channel the file lacks reads as
// `fill`.
Imf::Slice float_slice(float* pixels, const Imath::Box2i& window, int64_t width, int channel,
                       double fill) {
    const size_t x_stride = 4 * sizeof(float), y_stride = size_t(width) * x_stride;
    char* origin = reinterpret_cast<char*>(pixels + channel) -
                   int64_t(window.min.x) * int64_t(x_stride) -
                   int64_t(window.min.y) * int64_t(y_stride);
    return Imf::Slice(Imf::FLOAT, origin, x_stride, y_stride, 1, 1, fill);
}

bool read_exr(const void* bytes, size_t size, const DecodeLimits& limits, DecodedFile& out,
              std::string& error) {
    MemoryInput input(static_cast<const char*>(bytes), size);
    Imf::InputFile file(input, kNoThreads);
    const Imf::ChannelList& channels = file.header().channels();
    auto has = [&](const char* name) { return channels.findChannel(name) != nullptr; };
    const bool rgb = has("R") || has("G") || has("B");
    if (!rgb && !has("Y") && !has("A")) {
        error = "no R, G, B, A or Y channel to read";
        return false;
    }
    const Imath::Box2i window = file.header().dataWindow();
    const int64_t width = int64_t(window.max.x) - window.min.x + 1;
    const int64_t height = int64_t(window.max.y) - window.min.y + 1;
    if (!within_decode_limits(width, height, limits, error)) return false;
    // Read as float whatever the file stores (half, float or uint): a float file comes back
    // bit for bit. Luminance fills R, and G and B copy it.
    out.values.assign(size_t(width * height) * 4, 0.0f);
    float* pixels = out.values.data();
    Imf::FrameBuffer frame;
    frame.insert(rgb || !has("Y") ? "R" : "Y", float_slice(pixels, window, width, 0, 0.0));
    if (rgb) {
        frame.insert("G", float_slice(pixels, window, width, 1, 0.0));
        frame.insert("B", float_slice(pixels, window, width, 2, 0.0));
    }
    frame.insert("A", float_slice(pixels, window, width, 3, 1.0));
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    if (!rgb)
        for (size_t i = 0; i < size_t(width * height); ++i)
            pixels[i * 4 + 1] = pixels[i * 4 + 2] = pixels[i * 4];

    out.width = uint32_t(width);
    out.height = uint32_t(height);
    out.channels = 4;
    out.integer_format = false;
    out.straight_alpha = false;
    return true;
}

void write_half(uint32_t width, uint32_t height, const float* rgba,
                std::vector<unsigned char>& bytes) {
    std::vector<Imf::Rgba> pixels(size_t(width) * height);
    for (size_t i = 0; i < pixels.size(); ++i)
        pixels[i] = Imf::Rgba(rgba[i * 4], rgba[i * 4 + 1], rgba[i * 4 + 2], rgba[i * 4 + 3]);
    MemoryOutput output(bytes);
    Imf::Header header(static_cast<int>(width), static_cast<int>(height));
    header.compression() = Imf::ZIP_COMPRESSION;
    Imf::RgbaOutputFile file(output, header, Imf::WRITE_RGBA, kNoThreads);
    file.setFrameBuffer(pixels.data(), 1, width);
    file.writePixels(int(height));
}

void write_float(uint32_t width, uint32_t height, const float* rgba,
                 std::vector<unsigned char>& bytes) {
    MemoryOutput output(bytes);
    Imf::Header header(static_cast<int>(width), static_cast<int>(height));
    header.compression() = Imf::NO_COMPRESSION;
    const char* names[4] = {"R", "G", "B", "A"};
    for (const char* name : names) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    Imf::OutputFile file(output, header, kNoThreads);
    Imf::FrameBuffer frame;
    char* base = reinterpret_cast<char*>(const_cast<float*>(rgba));
    for (int c = 0; c < 4; ++c)
        frame.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), 4 * sizeof(float),
                                          size_t(width) * 4 * sizeof(float)));
    file.setFrameBuffer(frame);
    file.writePixels(int(height));
}

}  // namespace

bool is_exr(const void* bytes, size_t size) {
    static const unsigned char magic[4] = {0x76, 0x2f, 0x31, 0x01};
    return size >= 4 && std::memcmp(bytes, magic, 4) == 0;
}

bool decode_exr(const void* bytes, size_t size, const DecodeLimits& limits, DecodedFile& out,
                std::string& error) {
    try {
        return read_exr(bytes, size, limits, out, error);
    } catch (const std::exception& e) {
        error = e.what();
        return false;
    }
}

bool encode_exr(uint32_t width, uint32_t height, const float* rgba, bool full_float,
                std::vector<unsigned char>& out, std::string& error) {
    out.clear();
    try {
        if (full_float)
            write_float(width, height, rgba, out);
        else
            write_half(width, height, rgba, out);
        return true;
    } catch (const std::exception& e) {
        error = e.what();
        return false;
    }
}

}  // namespace acetate
