#include "test_files.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <atomic>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>

#include "scene/exr_file.hpp"
#include "scene/png_file.hpp"

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

namespace {

// Encoded bytes written as they are, or an exception naming the file.
std::filesystem::path write_encoded(const std::filesystem::path& file, bool ok,
                                    const std::vector<unsigned char>& bytes,
                                    const std::string& why) {
    if (!ok) throw std::runtime_error("cannot encode " + file.string() + ": " + why);
    std::ofstream out(file, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    if (!out) throw std::runtime_error("cannot write " + file.string());
    return file;
}

}  // namespace

std::filesystem::path write_exr(const std::filesystem::path& file, const ImageRGBA& image) {
    std::vector<unsigned char> bytes;
    std::string why;
    const bool ok = encode_exr(image.width, image.height, image.pixels.data(), true, bytes, why);
    return write_encoded(file, ok, bytes, why);
}

std::filesystem::path write_png8(const std::filesystem::path& file, uint32_t width, uint32_t height,
                                 const std::vector<uint8_t>& rgba8) {
    std::vector<unsigned char> bytes;
    std::string why;
    const bool ok = encode_png(width, height, rgba8.data(), bytes, why);
    return write_encoded(file, ok, bytes, why);
}

std::string shell_quote(const std::string& text) {
    std::string out = "'";
    for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

std::string read_file(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::vector<std::string> nonempty_lines(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        if (!line.empty()) lines.push_back(line);
    return lines;
}

std::string harness_environment() {
    std::string env = "ACETATE_VALIDATION=1";
    const std::filesystem::path cache =
        std::filesystem::temp_directory_path() / "acetate-harness-test-cache";
    for (const auto& [name, sub] :
         {std::pair{"MESA_SHADER_CACHE_DIR", "mesa"}, std::pair{"XDG_CACHE_HOME", "xdg"}}) {
        const char* set = std::getenv(name);
        std::string value = set && *set ? set : (cache / sub).string();
        std::filesystem::create_directories(value);
        env += std::string(" ") + name + "=" + shell_quote(value);
    }
    return env;
}

std::string CommandResult::describe() const {
    return "command: " + command + "\nexit code: " + std::to_string(code) + "\n--- stdout ---\n" +
           out + "--- stderr ---\n" + err;
}

CommandResult run_command(const std::string& command, const std::filesystem::path& capture_dir) {
    static std::atomic<int> counter{0};
    const std::string n = std::to_string(counter++);
    const auto out_file = capture_dir / ("command-" + n + ".stdout");
    const auto err_file = capture_dir / ("command-" + n + ".stderr");
    CommandResult result;
    result.command = command;
    const int raw = std::system(("(" + command + ") >" + shell_quote(out_file.string()) + " 2>" +
                                 shell_quote(err_file.string()) + " </dev/null")
                                    .c_str());
    result.code = raw != -1 && WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    result.out = read_file(out_file);
    result.err = read_file(err_file);
    return result;
}

std::filesystem::path write_edited_scene(const std::filesystem::path& scene,
                                         const std::function<void(nlohmann::json&)>& edit,
                                         const std::filesystem::path& out) {
    nlohmann::json json = nlohmann::json::parse(read_file(scene));
    const std::filesystem::path folder = scene.parent_path();
    for (nlohmann::json& floor : json["floors"])
        for (nlohmann::json& tile : floor["tiles"]) {
            tile["image"] = (folder / tile["image"].get<std::string>()).string();
            if (tile.contains("masks"))
                for (auto& [kind, mask] : tile["masks"].items())
                    mask = (folder / mask.get<std::string>()).string();
        }
    edit(json);
    return write_text(out, json.dump(2));
}

}  // namespace acetate::test
