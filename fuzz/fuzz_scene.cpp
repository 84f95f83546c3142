// Fuzzes the scene parser: any bytes give a scene or a one-line error, never a crash, a leak,
// undefined behaviour or a hang.
#include <cstddef>
#include <cstdint>
#include <string>

#include "scene/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    auto scene = acetate::parse_scene_text(text, "/nonexistent/fuzz/scene.json");
    if (!scene.ok() && scene.error().message.find('\n') != std::string::npos) __builtin_trap();
    return 0;
}
