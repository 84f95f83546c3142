#include "render/renderer.hpp"

#include <cstdio>

#include "vulkan/pipeline_cache_file.hpp"
#include "vulkan/vulkan_context.hpp"

namespace acetate {

Renderer::Renderer(VulkanContext& context, const RendererOptions& options)
    : context_(context), options_(options), plugins_(options.plugin_directories) {}

Result<std::unique_ptr<Renderer>> Renderer::create(VulkanContext& context,
                                                   const RendererOptions& options) {
    std::unique_ptr<Renderer> out(new Renderer(context, options));
    out->pool_ = std::make_unique<PipelinePool>(context);
    if (options.pipeline_cache_file) {
        auto data =
            read_pipeline_cache(*options.pipeline_cache_file, identity_of(context.properties()));
        if (!data) {
            // A bad or stale file is never handed to the driver; start empty and overwrite it.
            out->cache_warning_ = data.error().message;
            std::fprintf(stderr, "acetate: warning: ignoring the pipeline cache: %s\n",
                         data.error().message.c_str());
        } else if (!data->empty()) {
            ACETATE_TRY(out->pool_->seed_cache(data.value()));
        }
    }
    auto host = HostPipelines::create(context, *out->pool_);
    if (!host) return host.error();
    out->host_ = std::move(host.value());
    auto effects = EffectPipelines::create(context, *out->pool_);
    if (!effects) return effects.error();
    out->effects_ = std::move(effects.value());
    return out;
}

Renderer::~Renderer() {
    if (context_.device()) vkDeviceWaitIdle(context_.device());
}

Result<void> Renderer::save_pipeline_cache() {
    if (!options_.pipeline_cache_file) return {};
    auto data = pool_->cache_data();
    if (!data) return data.error();
    return write_pipeline_cache(*options_.pipeline_cache_file, identity_of(context_.properties()),
                                data.value());
}

}  // namespace acetate
