#pragma once
// GLSL -> SPIR-V with glslang, in process. The host compiles every shader it runs, so the
// compile counter in ResourceCounters sees all of them.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/result.hpp"

namespace acetate {

enum class ShaderStage { Vertex, Fragment };

// Compiles one GLSL 450 shader for Vulkan 1.3. `name` appears in errors, e.g.
// `shader "composite.frag": ERROR: 0:12: 'x' : undeclared identifier`.
// Thread-safe; glslang's process state is set up once on first use.
Result<std::vector<uint32_t>> compile_glsl(std::string_view name, ShaderStage stage,
                                           std::string_view source);

// Compiles a trivial vertex and fragment shader, so that glslang's process state and its
// built-in symbol tables for both stages (built on a stage's first compile and kept; most of
// what compiling a short shader costs) exist before a process is forked (core/fork_server.hpp).
void warm_shader_compiler();

// The host's own shaders, embedded at build time from host/shaders/ (empty if unknown).
std::string_view embedded_shader(std::string_view name);

}  // namespace acetate
