#include "core/output_paths.hpp"

#include <fmt/format.h>
#include <sys/stat.h>

#include <optional>

namespace acetate {
namespace {

namespace fs = std::filesystem;

// What makes two names one file: the device and inode of an existing file (links, "./x", hard
// links), else the normalised absolute path of one that does not exist yet.
struct FileIdentity {
    std::optional<std::pair<dev_t, ino_t>> inode;
    fs::path normalised;

    bool operator==(const FileIdentity& other) const {
        if (inode && other.inode) return *inode == *other.inode;
        return normalised == other.normalised;
    }
};

FileIdentity identify(const fs::path& path) {
    FileIdentity id;
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0) id.inode = std::pair(st.st_dev, st.st_ino);
    std::error_code ec;
    id.normalised = fs::weakly_canonical(fs::absolute(path, ec), ec);
    if (ec) id.normalised = path.lexically_normal();
    return id;
}

}  // namespace

Result<void> check_outputs_spare_inputs(const std::vector<RunFile>& outputs,
                                        const std::vector<RunFile>& inputs) {
    std::vector<FileIdentity> input_ids, output_ids;
    std::vector<size_t> previous;  // the index in `outputs` of each output_ids entry
    for (const RunFile& in : inputs) input_ids.push_back(identify(in.path));
    for (size_t o = 0; o < outputs.size(); ++o) {
        // A floor rendered twice (--floors 0,1,0) writes its one file twice: that is no clash.
        bool repeat = false;
        for (size_t earlier = 0; earlier < o; ++earlier)
            repeat = repeat || (outputs[earlier].path == outputs[o].path &&
                                outputs[earlier].role == outputs[o].role);
        if (repeat) continue;
        const FileIdentity id = identify(outputs[o].path);
        for (size_t i = 0; i < inputs.size(); ++i)
            if (id == input_ids[i])
                return make_error(
                    ErrorCode::InvalidInput,
                    fmt::format("{} {}: would overwrite an input of this run ({}: {})",
                                outputs[o].role, outputs[o].path.string(), inputs[i].role,
                                inputs[i].path.string()));
        for (size_t earlier = 0; earlier < output_ids.size(); ++earlier)
            if (id == output_ids[earlier])
                return make_error(
                    ErrorCode::InvalidInput,
                    fmt::format("{} {}: is also the output of {} ({})", outputs[o].role,
                                outputs[o].path.string(), outputs[previous[earlier]].role,
                                outputs[previous[earlier]].path.string()));
        output_ids.push_back(id);
        previous.push_back(o);
    }
    return {};
}

}  // namespace acetate
