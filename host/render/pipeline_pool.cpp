#include "render/pipeline_pool.hpp"

#include "core/sha256.hpp"
#include "vulkan/vk_check.hpp"
#include "vulkan/vulkan_context.hpp"

namespace acetate {

PipelinePool::PipelinePool(VulkanContext& context) : context_(context) {
    VkPipelineCacheCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
    vkCreatePipelineCache(context_.device(), &info, nullptr, &cache_);
}

PipelinePool::~PipelinePool() {
    VkDevice device = context_.device();
    for (auto& [key, pipeline] : pipelines_) vkDestroyPipeline(device, pipeline, nullptr);
    if (cache_) vkDestroyPipelineCache(device, cache_, nullptr);
}

Result<std::shared_ptr<const std::vector<uint32_t>>> PipelinePool::spirv(std::string_view name,
                                                                         ShaderStage stage,
                                                                         std::string_view source) {
    const std::string key = sha256_hex(source) + (stage == ShaderStage::Vertex ? ".vert" : ".frag");
    if (auto found = spirv_.find(key); found != spirv_.end()) return found->second;
    auto compiled = compile_glsl(name, stage, source);
    if (!compiled) return compiled.error();
    ++context_.counters().shaders_compiled;
    auto shared = std::make_shared<const std::vector<uint32_t>>(std::move(compiled.value()));
    spirv_.emplace(key, shared);
    return shared;
}

Result<VkPipeline> PipelinePool::pipeline(
    const std::string& key, const std::function<Result<VkPipeline>(VkPipelineCache)>& create) {
    if (auto found = pipelines_.find(key); found != pipelines_.end()) return found->second;
    auto created = create(cache_);
    if (!created) return created.error();
    ++context_.counters().pipelines_created;
    pipelines_.emplace(key, created.value());
    return created.value();
}

Result<VkShaderModule> PipelinePool::module(const std::vector<uint32_t>& spirv) {
    VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    info.codeSize = spirv.size() * sizeof(uint32_t);
    info.pCode = spirv.data();
    VkShaderModule module = VK_NULL_HANDLE;
    ACETATE_VK(vkCreateShaderModule(context_.device(), &info, nullptr, &module));
    return module;
}

Result<void> PipelinePool::seed_cache(const std::vector<uint8_t>& data) {
    VkPipelineCacheCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
    info.initialDataSize = data.size();
    info.pInitialData = data.data();
    VkPipelineCache seeded = VK_NULL_HANDLE;
    ACETATE_VK(vkCreatePipelineCache(context_.device(), &info, nullptr, &seeded));
    if (cache_) vkDestroyPipelineCache(context_.device(), cache_, nullptr);
    cache_ = seeded;
    return {};
}

Result<std::vector<uint8_t>> PipelinePool::cache_data() const {
    size_t size = 0;
    ACETATE_VK(vkGetPipelineCacheData(context_.device(), cache_, &size, nullptr));
    std::vector<uint8_t> data(size);
    ACETATE_VK(vkGetPipelineCacheData(context_.device(), cache_, &size, data.data()));
    data.resize(size);
    return data;
}

}  // namespace acetate
