#include "vulkan/shader_compiler.hpp"

#include <fmt/format.h>
#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>

#include <mutex>

namespace acetate {
namespace {

// glslang's InitializeProcess is process-global and must run once before any compile.
void ensure_glslang_initialised() {
    static std::once_flag once;
    std::call_once(once, [] {
        glslang::InitializeProcess();
        std::atexit([] { glslang::FinalizeProcess(); });
    });
}

std::string first_line(const std::string& log) {
    std::string s = log.substr(0, log.find('\n'));
    return s.empty() ? "unknown error" : s;
}

}  // namespace

Result<std::vector<uint32_t>> compile_glsl(std::string_view name, ShaderStage stage,
                                           std::string_view source) {
    ensure_glslang_initialised();
    const EShLanguage language = stage == ShaderStage::Vertex ? EShLangVertex : EShLangFragment;
    glslang::TShader shader(language);
    const std::string text(source);
    const char* strings[] = {text.c_str()};
    const std::string shader_name(name);
    const char* names[] = {shader_name.c_str()};
    shader.setStringsWithLengthsAndNames(strings, nullptr, names, 1);
    shader.setEnvInput(glslang::EShSourceGlsl, language, glslang::EShClientVulkan, 100);
    shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_3);
    shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_6);
    const auto messages = EShMessages(EShMsgSpvRules | EShMsgVulkanRules);
    if (!shader.parse(GetDefaultResources(), 450, false, messages))
        return make_error(ErrorCode::ShaderCompile,
                          fmt::format("shader \"{}\": {}", name, first_line(shader.getInfoLog())));
    glslang::TProgram program;
    program.addShader(&shader);
    if (!program.link(messages))
        return make_error(ErrorCode::ShaderCompile, fmt::format("shader \"{}\": link: {}", name,
                                                                first_line(program.getInfoLog())));
    std::vector<uint32_t> spirv;
    glslang::SpvOptions options;
    options.disableOptimizer = false;
    glslang::GlslangToSpv(*program.getIntermediate(language), spirv, &options);
    return spirv;
}

void warm_shader_compiler() {
    (void)compile_glsl("warm-up.vert", ShaderStage::Vertex,
                       "#version 450\nvoid main() { gl_Position = vec4(0.0); }\n");
    (void)compile_glsl("warm-up.frag", ShaderStage::Fragment,
                       "#version 450\nlayout(location = 0) out vec4 colour;\n"
                       "void main() { colour = vec4(0.0); }\n");
}

}  // namespace acetate
