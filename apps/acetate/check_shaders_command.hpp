#pragma once
// `acetate check-shaders PLUGIN.so [--shader FILE]...`: compiles every GLSL pass the plugin's
// build() declares, with the preamble the host puts before it at load (plain, and with the
// harness's checked built-ins), so a GLSL error fails the plugin's build instead of a scene's
// load. acetate_add_effect runs it after linking, with the plugin's SHADERS (cmake/
// AcetateEffect.cmake). Errors read `tint.frag:12: error: 'x' : undeclared identifier (pass
// "floor0.example.tint.shade", preset "high")` when a pass's text comes from one of the shader
// files, else they name the pass.

#include <filesystem>
#include <vector>

namespace acetate {

struct CheckShadersCommand {
    std::filesystem::path plugin;
    std::vector<std::filesystem::path> shaders;  // the files the passes' text comes from
};

// 0 when every pass compiled, 1 with one line per error on stderr.
int run_check_shaders(const CheckShadersCommand& command);

}  // namespace acetate
