// Fuzzes the image loader (libpng and OpenEXR for PNG and EXR, OpenImageIO's module for any
// other format, each behind our checks: sizes, channels, finiteness, premultiplication): any
// file gives an image or a one-line error. The bytes are written to a file because the loader
// reads files; the first byte picks the extension, so both formats a scene uses are reached.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "scene/image_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 1) return 0;
    static const std::filesystem::path dir = [] {
        auto d = std::filesystem::temp_directory_path() /
                 ("acetate-fuzz-image-" + std::to_string(::getpid()));
        std::filesystem::create_directories(d);
        return d;
    }();
    const std::filesystem::path file = dir / (data[0] % 2 ? "input.exr" : "input.png");
    {
        std::ofstream out(file, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data + 1), std::streamsize(size - 1));
    }
    const auto role = data[0] & 2 ? acetate::ImageRole::Mask : acetate::ImageRole::Colour;
    auto image = acetate::load_image(file, role);
    if (!image.ok() && image.error().message.find('\n') != std::string::npos) __builtin_trap();
    return 0;
}
