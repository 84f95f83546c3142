// Loads libacetate-image-codec.so (scene/image_codec.hpp) from the folder libacetate-host.so
// itself was loaded from: where the build puts both, and where the install does.

#include "scene/image_codec.hpp"

#include <dlfcn.h>
#include <fmt/format.h>

#include <filesystem>
#include <mutex>

namespace acetate {
namespace {

// This library's own file, as the dynamic loader mapped it.
std::filesystem::path host_library_file() {
    Dl_info info{};
    if (dladdr(reinterpret_cast<const void*>(&host_library_file), &info) == 0 ||
        info.dli_fname == nullptr)
        return {};
    return info.dli_fname;
}

Result<const ImageCodec*> load_codec() {
    const std::filesystem::path host = host_library_file();
    if (host.empty())
        return make_error(ErrorCode::ImageDecode,
                          "cannot find the image codec: the host library does not know its file");
    const std::filesystem::path module =
        std::filesystem::absolute(host).parent_path() / kImageCodecFile;
    // Never unloaded: the table it returns lives as long as the process.
    void* handle = dlopen(module.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle)
        return make_error(ErrorCode::ImageDecode, fmt::format("cannot load the image codec {}: {}",
                                                              module.string(), dlerror()));
    using Entry = const ImageCodec* (*)();
    auto entry = reinterpret_cast<Entry>(dlsym(handle, kImageCodecEntry));
    const ImageCodec* codec = entry ? entry() : nullptr;
    if (!codec || !codec->decode)
        return make_error(ErrorCode::ImageDecode,
                          fmt::format("{} is not an Acetate image codec (no {})", module.string(),
                                      kImageCodecEntry));
    return codec;
}

}  // namespace

Result<const ImageCodec*> image_codec() {
    static std::once_flag once;
    static Result<const ImageCodec*> loaded = make_error(ErrorCode::ImageDecode, "");
    std::call_once(once, [] { loaded = load_codec(); });
    return loaded;
}

}  // namespace acetate
