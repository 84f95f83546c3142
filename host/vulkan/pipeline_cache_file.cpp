#include "vulkan/pipeline_cache_file.hpp"

#include <fmt/format.h>
#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <system_error>

#include "core/atomic_file.hpp"
#include "core/input_file.hpp"
#include "core/sha256.hpp"

namespace acetate {
namespace {

namespace fs = std::filesystem;

// Layout of our header; see the table in the .hpp.
constexpr std::array<uint8_t, 12> kMagic = {'A', 'C', 'E', 'T', 'A', 'T', 'E', 'P', 'C', 0, 0, 0};
constexpr uint32_t kFormatVersion = 1;
constexpr size_t kSha256Size = 32;
constexpr size_t kUuidOffset = 28;
constexpr size_t kDataSizeOffset = kUuidOffset + VK_UUID_SIZE;  // 44
constexpr size_t kHashOffset = kDataSizeOffset + 8;             // 52
constexpr size_t kHeaderSize = kHashOffset + kSha256Size;       // 84

// sizeof(VkPipelineCacheHeaderVersionOne): the least any driver header can be.
constexpr size_t kDriverHeaderSize = 16 + VK_UUID_SIZE;
static_assert(sizeof(VkPipelineCacheHeaderVersionOne) == kDriverHeaderSize);

static_assert(sizeof(Sha256Digest) == kSha256Size);

// Explicit little-endian coding: the Vulkan spec fixes the driver header's byte order this way
// too, and it keeps the format independent of struct padding.
void put_u32(std::vector<uint8_t>& out, uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(uint8_t(v >> (8 * i)));
}
void put_u64(std::vector<uint8_t>& out, uint64_t v) {
    for (int i = 0; i < 8; ++i) out.push_back(uint8_t(v >> (8 * i)));
}
uint32_t get_u32(std::span<const uint8_t> in, size_t at) {
    uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= uint32_t(in[at + i]) << (8 * i);
    return v;
}
uint64_t get_u64(std::span<const uint8_t> in, size_t at) {
    uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= uint64_t(in[at + i]) << (8 * i);
    return v;
}

std::string hex(std::span<const uint8_t> bytes) {
    std::string s;
    for (uint8_t b : bytes) s += fmt::format("{:02x}", b);
    return s;
}

Error invalid(std::string_view name, std::string_view what) {
    return make_error(ErrorCode::InvalidInput, fmt::format("{}: {}", name, what));
}

// Compares one identity field; the message says which one is stale and both values.
Result<void> same_u32(std::string_view name, std::string_view prefix, std::string_view field,
                      uint32_t stored, uint32_t current) {
    if (stored == current) return {};
    return invalid(
        name, fmt::format("{}: {} {:#x}, this device has {:#x}", prefix, field, stored, current));
}

}  // namespace

PipelineCacheIdentity identity_of(const VkPhysicalDeviceProperties& properties) {
    PipelineCacheIdentity id;
    id.vendor_id = properties.vendorID;
    id.device_id = properties.deviceID;
    id.driver_version = properties.driverVersion;
    std::copy(std::begin(properties.pipelineCacheUUID), std::end(properties.pipelineCacheUUID),
              id.pipeline_cache_uuid.begin());
    return id;
}

fs::path default_pipeline_cache_path() {
    const fs::path tail = fs::path("acetate") / "pipeline-cache.bin";
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && fs::path(xdg).is_absolute())
        return fs::path(xdg) / tail;
    if (const char* home = std::getenv("HOME"); home && *home)
        return fs::path(home) / ".cache" / tail;
    return {};
}

Result<void> check_driver_header(std::span<const uint8_t> data, const PipelineCacheIdentity& id,
                                 std::string_view name) {
    const std::string_view p = "driver header";
    if (data.size() < kDriverHeaderSize)
        return invalid(
            name, fmt::format("{}: {} bytes, need at least {}", p, data.size(), kDriverHeaderSize));
    const uint32_t header_size = get_u32(data, 0);
    if (header_size < kDriverHeaderSize || header_size > data.size())
        return invalid(name, fmt::format("{}: headerSize {} outside [{}, {}]", p, header_size,
                                         kDriverHeaderSize, data.size()));
    if (const uint32_t version = get_u32(data, 4); version != VK_PIPELINE_CACHE_HEADER_VERSION_ONE)
        return invalid(name, fmt::format("{}: headerVersion {}, expected {}", p, version,
                                         int(VK_PIPELINE_CACHE_HEADER_VERSION_ONE)));
    ACETATE_TRY(same_u32(name, p, "vendor id", get_u32(data, 8), id.vendor_id));
    ACETATE_TRY(same_u32(name, p, "device id", get_u32(data, 12), id.device_id));
    const auto uuid = data.subspan(16, VK_UUID_SIZE);
    if (!std::equal(uuid.begin(), uuid.end(), id.pipeline_cache_uuid.begin()))
        return invalid(name, fmt::format("{}: pipeline cache UUID {}, this device has {}", p,
                                         hex(uuid), hex(id.pipeline_cache_uuid)));
    return {};
}

Result<std::vector<uint8_t>> encode_pipeline_cache(const PipelineCacheIdentity& id,
                                                   std::span<const uint8_t> data) {
    const Sha256Digest digest = sha256_digest(data.data(), data.size());
    std::vector<uint8_t> out;
    out.reserve(kHeaderSize + data.size());
    out.insert(out.end(), kMagic.begin(), kMagic.end());
    put_u32(out, kFormatVersion);
    put_u32(out, id.vendor_id);
    put_u32(out, id.device_id);
    put_u32(out, id.driver_version);
    out.insert(out.end(), id.pipeline_cache_uuid.begin(), id.pipeline_cache_uuid.end());
    put_u64(out, data.size());
    out.insert(out.end(), digest.begin(), digest.end());
    out.insert(out.end(), data.begin(), data.end());
    return out;
}

// The checks run cheapest and most telling first: a file from another program fails on the
// magic, one from another device on the identity, and only a damaged one reaches the hash.
Result<std::vector<uint8_t>> decode_pipeline_cache(std::span<const uint8_t> bytes,
                                                   const PipelineCacheIdentity& id,
                                                   std::string_view name) {
    const size_t magic_seen = std::min(bytes.size(), kMagic.size());
    if (!std::equal(bytes.begin(), bytes.begin() + magic_seen, kMagic.begin()))
        return invalid(name, "bad magic: not an Acetate pipeline cache file");
    if (bytes.size() < kHeaderSize)
        return invalid(name, fmt::format("truncated: {} bytes, the header alone needs {}",
                                         bytes.size(), kHeaderSize));
    if (const uint32_t version = get_u32(bytes, 12); version != kFormatVersion)
        return invalid(name,
                       fmt::format("format version {}, expected {}", version, kFormatVersion));
    const std::string_view stale = "stale";
    ACETATE_TRY(same_u32(name, stale, "vendor id", get_u32(bytes, 16), id.vendor_id));
    ACETATE_TRY(same_u32(name, stale, "device id", get_u32(bytes, 20), id.device_id));
    ACETATE_TRY(same_u32(name, stale, "driver version", get_u32(bytes, 24), id.driver_version));
    const auto uuid = bytes.subspan(kUuidOffset, VK_UUID_SIZE);
    if (!std::equal(uuid.begin(), uuid.end(), id.pipeline_cache_uuid.begin()))
        return invalid(name, fmt::format("stale: pipeline cache UUID {}, this device has {}",
                                         hex(uuid), hex(id.pipeline_cache_uuid)));
    const uint64_t data_size = get_u64(bytes, kDataSizeOffset);
    const auto data = bytes.subspan(kHeaderSize);
    if (data_size != data.size())
        return invalid(name, fmt::format("data size mismatch: the header says {} bytes, {} follow"
                                         " (truncated or overwritten)",
                                         data_size, data.size()));
    const Sha256Digest digest = sha256_digest(data.data(), data.size());
    if (!std::equal(digest.begin(), digest.end(), bytes.begin() + kHashOffset))
        return invalid(name, "hash mismatch: the SHA-256 of the data differs from the header");
    ACETATE_TRY(check_driver_header(data, id, name));
    return std::vector<uint8_t>(data.begin(), data.end());
}

Result<std::vector<uint8_t>> read_pipeline_cache(const fs::path& file,
                                                 const PipelineCacheIdentity& id) {
    // The one input reader: a FIFO or a device here is refused, never waited on or read whole.
    auto text = read_input_file_if_exists(file, kMaxPipelineCacheBytes, "a pipeline cache");
    if (!text) return text.error();
    if (!text.value()) return std::vector<uint8_t>{};
    const std::string& data = **text;
    return decode_pipeline_cache(
        std::span(reinterpret_cast<const uint8_t*>(data.data()), data.size()), id, file.string());
}

Result<void> write_pipeline_cache(const fs::path& file, const PipelineCacheIdentity& id,
                                  std::span<const uint8_t> driver_data) {
    // Writing data the reader would reject only wastes a write and a warning next run.
    ACETATE_TRY(check_driver_header(driver_data, id, file.string()));
    auto encoded = encode_pipeline_cache(id, driver_data);
    if (!encoded) return encoded.error();
    if (file.has_parent_path()) {
        std::error_code ec;
        fs::create_directories(file.parent_path(), ec);
        if (ec)
            return make_error(ErrorCode::Io,
                              fmt::format("{}: cannot create directory {}: {}", file.string(),
                                          file.parent_path().string(), ec.message()));
    }
    const auto& b = *encoded;
    return write_file_atomically(
        file, std::string_view(reinterpret_cast<const char*>(b.data()), b.size()));
}

}  // namespace acetate
