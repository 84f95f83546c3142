#include "api_host.hpp"

namespace acetate::test {

host::Result<std::unique_ptr<host::Host>> build_tree_host() {
    host::HostOptions options;
    options.pipeline_cache = false;
    options.allow_unvalidated = true;
    options.plugin_directories = {ACETATE_PLUGIN_DIR};
    options.on_warning = [](const std::string&) {};
    return host::Host::create(options);
}

std::filesystem::path quay_scene(const std::string& plugin) {
    return std::filesystem::path(ACETATE_SOURCE_VALIDATION_DIR) / "references" / plugin / "scenes" /
           "quay.json";
}

}  // namespace acetate::test
