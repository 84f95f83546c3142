// embedded_shader(): the host's own GLSL, looked up by file name in the header the build
// generates from host/shaders/ (cmake/AcetateEmbedGlsl.cmake, the script plugins use too).
#include "host_shaders.hpp"
#include "vulkan/shader_compiler.hpp"

namespace acetate {

std::string_view embedded_shader(std::string_view name) {
    for (const auto& [file, text] : acetate_embedded_glsl)
        if (file == name) return text;
    return {};
}

}  // namespace acetate
