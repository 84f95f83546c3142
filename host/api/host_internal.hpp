#pragma once
// What the embedding API's two files share (host.cpp: Host; scene.cpp: Scene): the state
// behind a Host and a Scene, and errors translated to the API's own.

#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "acetate/host/host.hpp"
#include "core/result.hpp"
#include "render/compositor.hpp"
#include "render/renderer.hpp"
#include "scene/scene.hpp"
#include "vulkan/vulkan_context.hpp"

namespace acetate::host {

// The device and the renderer outlive every scene loaded on them: each Scene holds this.
struct Host::State {
    std::unique_ptr<VulkanContext> context;
    std::unique_ptr<Renderer> renderer;
    std::function<void(const std::string&)> warn;
    bool load_plugins = true;  // HostOptions::load_plugins
    // Held by every call of the Host and its Scenes that touches the device, the renderer or a
    // scene: the queue, the pipeline pool, the plugin loader and the validation messages are
    // shared and unsynchronised, so calls from several threads run one after another (a load
    // on one thread waits for a frame on another, and the reverse) instead of racing.
    mutable std::mutex calls;
    // The scenes loaded on this Host and not yet destroyed (under `calls`): reload_plugins()
    // loads again those that use a changed plugin.
    std::vector<Scene::Loaded*> scenes;
};

struct Scene::Loaded {
    std::shared_ptr<Host::State> host;
    SceneDesc desc;
    std::unique_ptr<Compositor> compositor;
    CompositorOptions options;  // what it was loaded with (a live change may load it again)
    LoadStatistics load;
    uint32_t active_floor = 0;
    double time = 0;
    std::optional<Camera> camera;  // as set_camera was given it; none: the whole canvas
    bool rendered = false;
};

// The scene `desc` loaded again for `loaded` (a changed plugin, a live change the plan depends
// on): with its load options and the camera its current compositor renders through.
acetate::Result<std::unique_ptr<Compositor>> load_again(const Scene::Loaded& loaded,
                                                        const SceneDesc& desc);

inline Error error_of(const acetate::Error& e) {
    // The public codes are the internal ones, in the same order (checked in host.cpp).
    return Error{e.message, ErrorCode(int(e.code)), e.file, e.field, e.plugin, e.floor};
}

}  // namespace acetate::host
