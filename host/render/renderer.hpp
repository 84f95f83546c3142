#pragma once
// Process-wide rendering state that outlives scenes: the pipeline pool, the host stages, the
// effect pipeline layout, the plugin loader and the on-disk pipeline cache. A Compositor (one
// per loaded scene) borrows it.

#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "core/result.hpp"
#include "plugins/plugin_loader.hpp"
#include "render/effect_pipelines.hpp"
#include "render/host_pipelines.hpp"
#include "render/pipeline_pool.hpp"

namespace acetate {

class VulkanContext;

struct RendererOptions {
    std::vector<std::filesystem::path> plugin_directories;  // searched in order
    // Where the VkPipelineCache is kept between processes; empty: no disk cache.
    std::optional<std::filesystem::path> pipeline_cache_file;
};

class Renderer {
  public:
    // Loads the disk pipeline cache if present and valid; a bad or stale file is ignored with a
    // warning on stderr (never handed to the driver).
    static Result<std::unique_ptr<Renderer>> create(VulkanContext& context,
                                                    const RendererOptions& options);
    ~Renderer();

    VulkanContext& context() { return context_; }
    PipelinePool& pool() { return *pool_; }
    HostPipelines& host_pipelines() { return *host_; }
    EffectPipelines& effect_pipelines() { return *effects_; }
    PluginLoader& plugins() { return plugins_; }

    // Writes the pipeline cache file atomically (no-op without one).
    Result<void> save_pipeline_cache();
    // Why the cache file was not used at start-up, if it was not ("" if it was or none existed).
    const std::string& pipeline_cache_warning() const { return cache_warning_; }

  private:
    Renderer(VulkanContext& context, const RendererOptions& options);
    VulkanContext& context_;
    RendererOptions options_;
    std::unique_ptr<PipelinePool> pool_;
    std::unique_ptr<HostPipelines> host_;
    std::unique_ptr<EffectPipelines> effects_;
    PluginLoader plugins_;
    std::string cache_warning_;
};

}  // namespace acetate
