// Fuzzes the pipeline-cache reader: every check runs before a byte could reach a driver; any
// bytes give the driver data or a one-line error.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "vulkan/pipeline_cache_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    acetate::PipelineCacheIdentity identity;
    identity.vendor_id = 0x10005;
    identity.device_id = 0;
    for (size_t i = 0; i < identity.pipeline_cache_uuid.size(); ++i)
        identity.pipeline_cache_uuid[i] = uint8_t(i);
    auto decoded = acetate::decode_pipeline_cache(std::span(data, size), identity, "fuzz.bin");
    if (!decoded.ok() && decoded.error().message.find('\n') != std::string::npos) __builtin_trap();
    return 0;
}
