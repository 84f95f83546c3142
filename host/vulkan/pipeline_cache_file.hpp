#pragma once
// The on-disk VkPipelineCache: pipelines compiled in one run seed the driver in the next, so a
// real GPU does not recompile every shader at start-up (docs/design.md, L-pool). On lavapipe the
// driver's data is a 32-byte header only (docs/design.md, "Facts about lavapipe"); the logic
// still runs there.
//
// A driver must never see bytes it did not write for this exact device and driver: malformed
// cache data is undefined behaviour in some drivers. So the driver's data is wrapped in our own
// header, and every check below passes before the bytes are handed to vkCreatePipelineCache.
// A file that fails a check is not an emergency: the caller logs the error as a warning and
// starts with an empty cache; the next save replaces the file.
//
// File format, version 1. All integers little-endian; offsets in bytes.
//    0  12  magic "ACETATEPC" followed by three zero bytes
//   12   4  format version (1)
//   16   4  VkPhysicalDeviceProperties::vendorID
//   20   4  VkPhysicalDeviceProperties::deviceID
//   24   4  VkPhysicalDeviceProperties::driverVersion
//   28  16  VkPhysicalDeviceProperties::pipelineCacheUUID
//   44   8  data size N
//   52  32  SHA-256 of the data
//   84   N  data: exactly what vkGetPipelineCacheData returned, starting with the driver's own
//           VkPipelineCacheHeaderVersionOne (also checked against the device on read)
// Anything after the data is an error (the size field must account for every byte).

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string_view>
#include <vector>

#include "core/result.hpp"

namespace acetate {

// What the cached data is only valid for. A change to any field makes a saved file stale.
struct PipelineCacheIdentity {
    uint32_t vendor_id = 0;
    uint32_t device_id = 0;
    uint32_t driver_version = 0;
    std::array<uint8_t, VK_UUID_SIZE> pipeline_cache_uuid{};

    bool operator==(const PipelineCacheIdentity&) const = default;
};

// The identity of the device whose properties these are.
PipelineCacheIdentity identity_of(const VkPhysicalDeviceProperties& properties);

// $XDG_CACHE_HOME/acetate/pipeline-cache.bin, else $HOME/.cache/acetate/pipeline-cache.bin.
// A relative XDG_CACHE_HOME is ignored (the XDG spec says so). Empty when neither variable
// gives a location; the caller then runs without a persistent cache.
std::filesystem::path default_pipeline_cache_path();

// The driver data stored in `file`, ready for VkPipelineCacheCreateInfo::pInitialData.
// A missing file gives an empty vector (first run; not an error). A file that fails any check
// gives an InvalidInput error whose one-line message names the file and the check (bad magic,
// format version, stale vendor/device/driver/UUID, truncated or size mismatch, hash mismatch,
// driver header); Io when the file exists but cannot be read.
Result<std::vector<uint8_t>> read_pipeline_cache(const std::filesystem::path& file,
                                                 const PipelineCacheIdentity& identity);

// Saves `driver_data` (from vkGetPipelineCacheData) to `file` with its header: creates the
// directory, then writes atomically, so a reader sees the old file or the new one, never a
// mix. Fails with InvalidInput, writing nothing, when the driver data's own header does not
// match `identity` (the reader would reject it); Io when the directory or file cannot be
// written, leaving any old file untouched.
Result<void> write_pipeline_cache(const std::filesystem::path& file,
                                  const PipelineCacheIdentity& identity,
                                  std::span<const uint8_t> driver_data);

// The two halves of the above without the file system; exposed for tests and tools.
// encode: the whole file's bytes (no checks on driver_data; fails only if hashing fails).
Result<std::vector<uint8_t>> encode_pipeline_cache(const PipelineCacheIdentity& identity,
                                                   std::span<const uint8_t> driver_data);
// decode: every check of read_pipeline_cache on `bytes`; messages start with `name`.
Result<std::vector<uint8_t>> decode_pipeline_cache(std::span<const uint8_t> bytes,
                                                   const PipelineCacheIdentity& identity,
                                                   std::string_view name);
// The driver data's own VkPipelineCacheHeaderVersionOne against `identity`; messages start
// with `name`.
Result<void> check_driver_header(std::span<const uint8_t> driver_data,
                                 const PipelineCacheIdentity& identity, std::string_view name);

}  // namespace acetate
