#pragma once
// Process-wide store of compiled shaders and pipelines, owned by the Renderer so that it outlives
// every scene (docs/design.md, L-pool). Shaders are keyed by the SHA-256 of their source,
// pipelines by the key their maker gives (a host stage's name and colour format; an effect
// pass's SPIR-V hash plus its state), so loading a scene a second time compiles nothing and
// creates no pipeline.

#include <vulkan/vulkan.h>

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/result.hpp"
#include "vulkan/shader_compiler.hpp"

namespace acetate {

class VulkanContext;

class PipelinePool {
  public:
    explicit PipelinePool(VulkanContext& context);
    ~PipelinePool();
    PipelinePool(const PipelinePool&) = delete;
    PipelinePool& operator=(const PipelinePool&) = delete;

    // SPIR-V for this GLSL, compiled on first request only (counted in shaders_compiled).
    Result<std::shared_ptr<const std::vector<uint32_t>>> spirv(std::string_view name,
                                                               ShaderStage stage,
                                                               std::string_view source);

    // The pipeline stored under `key`, created by `create` on first request (counted in
    // pipelines_created). `create` receives the pool's VkPipelineCache.
    Result<VkPipeline> pipeline(const std::string& key,
                                const std::function<Result<VkPipeline>(VkPipelineCache)>& create);

    // A shader module for SPIR-V; the caller destroys it after creating its pipeline.
    Result<VkShaderModule> module(const std::vector<uint32_t>& spirv);

    VkPipelineCache cache() const { return cache_; }
    size_t pipeline_count() const { return pipelines_.size(); }

    // Seeds the driver cache from `data` (already checked by the caller); replaces the empty
    // cache made at construction. Call before creating any pipeline.
    Result<void> seed_cache(const std::vector<uint8_t>& data);
    // The driver's cache data, for saving.
    Result<std::vector<uint8_t>> cache_data() const;

  private:
    VulkanContext& context_;
    VkPipelineCache cache_ = VK_NULL_HANDLE;
    std::map<std::string, std::shared_ptr<const std::vector<uint32_t>>> spirv_;
    std::map<std::string, VkPipeline> pipelines_;
};

}  // namespace acetate
