#include "test_files.hpp"

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <fstream>
#include <stdexcept>

namespace acetate::test {

std::filesystem::path scratch_dir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = "acetate-test";
    if (info) name += std::string("-") + info->test_suite_name() + "-" + info->name();
    for (char& c : name)
        if (c == '/') c = '_';
    const auto dir = std::filesystem::temp_directory_path() / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

std::filesystem::path write_text(const std::filesystem::path& file, const std::string& text) {
    std::ofstream out(file, std::ios::binary);
    out << text;
    if (!out) throw std::runtime_error("cannot write " + file.string());
    return file;
}

std::filesystem::path write_exr(const std::filesystem::path& file, const ImageRGBA& image) {
    auto out = OIIO::ImageOutput::create(file.string());
    if (!out) throw std::runtime_error("cannot create " + file.string());
    OIIO::ImageSpec spec(int(image.width), int(image.height), 4, OIIO::TypeDesc::FLOAT);
    spec.attribute("compression", "none");
    if (!out->open(file.string(), spec) ||
        !out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data()) || !out->close())
        throw std::runtime_error("cannot write " + file.string());
    return file;
}

}  // namespace acetate::test
