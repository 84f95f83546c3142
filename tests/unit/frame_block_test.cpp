// The frame block (AcetateFrame) is laid out once, in EffectFrameLayout: the host writes each
// member at the float the layout names, so the layout must be where glslang puts each member
// of the block the preamble declares, for any count of parameters and phases, in both
// declarations (the storage block GLSL passes read, the uniform block of whole SPIR-V
// modules), and in the host's own instanced-quad vertex shader, which declares the first
// three members. Read from the SPIR-V itself: each member's Offset decoration. No device.

#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "render/effect_frame_layout.hpp"
#include "render/effect_pipelines.hpp"
#include "vulkan/shader_compiler.hpp"

namespace acetate {
namespace {

// Byte offset of every member of the struct named `block` in a SPIR-V module, by name.
std::map<std::string, uint32_t> member_offsets(const std::vector<uint32_t>& spirv,
                                               const std::string& block) {
    constexpr uint32_t kOpName = 5, kOpMemberName = 6, kOpMemberDecorate = 72,
                       kDecorationOffset = 35;
    auto text = [&](size_t word) {
        return std::string(reinterpret_cast<const char*>(&spirv[word]));
    };
    uint32_t block_id = 0;
    std::map<std::pair<uint32_t, uint32_t>, std::string> names;
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> offsets;
    for (size_t at = 5; at < spirv.size();) {  // after the header
        const uint32_t count = spirv[at] >> 16, opcode = spirv[at] & 0xffff;
        if (count == 0 || at + count > spirv.size()) break;
        if (opcode == kOpName && text(at + 2) == block) block_id = spirv[at + 1];
        if (opcode == kOpMemberName) names[{spirv[at + 1], spirv[at + 2]}] = text(at + 3);
        if (opcode == kOpMemberDecorate && spirv[at + 3] == kDecorationOffset)
            offsets[{spirv[at + 1], spirv[at + 2]}] = spirv[at + 4];
        at += count;
    }
    std::map<std::string, uint32_t> out;
    for (const auto& [key, name] : names)
        if (key.first == block_id && offsets.count(key)) out[name] = offsets.at(key);
    return out;
}

EffectDescriptor effect_with(size_t params) {
    EffectDescriptor d;
    d.id = "test.frame_block";
    for (size_t i = 0; i < params; ++i) {
        EffectParam p;
        p.name = "p" + std::to_string(i);
        p.type = i % 2 ? ACETATE_PARAM_COLOR : ACETATE_PARAM_FLOAT;
        p.max_value = 1;
        d.params.push_back(p);
    }
    return d;
}

TEST(FrameBlock, EveryMemberIsWhereTheLayoutWritesItForAnyCounts) {
    for (const auto& [params, phases] :
         std::vector<std::pair<size_t, size_t>>{{0, 0}, {1, 0}, {0, 3}, {3, 2}, {16, 8}}) {
        for (FrameBlockDeclaration declaration :
             {FrameBlockDeclaration::Storage, FrameBlockDeclaration::Uniform}) {
            SCOPED_TRACE(
                ::testing::Message()
                << params << " parameters, " << phases << " phases, "
                << (declaration == FrameBlockDeclaration::Storage ? "storage" : "uniform"));
            std::vector<GraphPhase> phase_list;
            for (size_t i = 0; i < phases; ++i) phase_list.push_back({"ph" + std::to_string(i), 2});
            GraphPass pass;
            pass.name = "p";
            const std::string source =
                effect_glsl_preamble(effect_with(params), pass, phase_list, false, declaration) +
                "void main() { out_color = acetate_canvas; }\n";
            auto spirv = compile_glsl("frame_block", ShaderStage::Fragment, source);
            ASSERT_TRUE(spirv.ok()) << spirv.error().message;
            const auto offsets = member_offsets(*spirv, "AcetateFrame");
            const EffectFrameLayout layout(params, phases);
            ASSERT_EQ(offsets.size(), EffectFrameLayout::kMembers.size());
            for (const auto& member : EffectFrameLayout::kMembers) {
                const std::string name(member.name);
                ASSERT_TRUE(offsets.count(name)) << name;
                EXPECT_EQ(offsets.at(name), layout.offset(name).value() * sizeof(float)) << name;
            }
            // What the host writes by accessor, and the buffer's size: the last phase ends it.
            EXPECT_EQ(layout.param(0), layout.offset("acetate_params"));
            EXPECT_EQ(layout.phase(0), layout.offset("acetate_phases"));
            EXPECT_EQ(layout.bytes(),
                      (layout.phase(std::max<size_t>(1, phases) - 1) + 4) * sizeof(float));
        }
    }
}

TEST(FrameBlock, TheInstancedQuadShaderReadsTheSameFirstMembers) {
    auto spirv = compile_glsl("instanced_quad.vert", ShaderStage::Vertex,
                              embedded_shader("instanced_quad.vert"));
    ASSERT_TRUE(spirv.ok()) << spirv.error().message;
    const auto offsets = member_offsets(*spirv, "AcetateFrame");
    const EffectFrameLayout layout(2, 1);
    ASSERT_EQ(offsets.size(), 3u);
    EXPECT_EQ(offsets.at("acetate_canvas"), layout.canvas() * sizeof(float));
    EXPECT_EQ(offsets.at("acetate_output"), layout.output() * sizeof(float));
    EXPECT_EQ(offsets.at("acetate_misc"), layout.misc() * sizeof(float));
}

TEST(FrameBlock, ANameTheBlockLacksHasNoOffset) {
    EXPECT_FALSE(EffectFrameLayout(1, 1).offset("acetate_time").has_value());
}

}  // namespace
}  // namespace acetate
