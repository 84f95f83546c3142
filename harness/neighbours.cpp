#include "neighbours.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>

#include "core/sha256.hpp"

namespace acetate::harness {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kPrefix = "acetate.harness.";

}  // namespace

std::string spread_neighbour_id(bool global) {
    return fmt::format("{}spread_{}", kPrefix, global ? "global" : "floor");
}

fs::path neighbour_directory(const fs::path& harness_program) {
    // The program may be named through a link (/proc/self/exe): its folder is the target's.
    std::error_code ec;
    const fs::path program = fs::weakly_canonical(harness_program, ec);
    const fs::path bin = (ec ? harness_program : program).parent_path();
    const fs::path build_tree = bin / "neighbours";
    if (fs::is_directory(build_tree, ec)) return build_tree;
    return bin.parent_path() / ACETATE_INSTALL_LIBDIR / "acetate" / "harness-neighbours";
}

Result<void> attach_neighbours(std::vector<CaseSpec>& cases, const fs::path& directory) {
    std::map<std::string, CompanionPlugin> found;  // each file hashed once per run
    for (CaseSpec& spec : cases) {
        std::vector<std::string> ids = spec.effects_before;
        ids.insert(ids.end(), spec.effects_after.begin(), spec.effects_after.end());
        for (const std::string& id : ids) {
            const bool attached = std::any_of(spec.companions.begin(), spec.companions.end(),
                                              [&](const CompanionPlugin& c) { return c.id == id; });
            if (attached) continue;
            auto known = found.find(id);
            if (known == found.end()) {
                // The file is named after the id without its prefix: spread_floor.so.
                const fs::path file = directory / (id.substr(kPrefix.size()) + ".so");
                auto sha = file_sha256(file);
                if (!sha)
                    return make_error(ErrorCode::Io,
                                      fmt::format("{}: the harness's neighbour effect {} is "
                                                  "missing or unreadable (is the harness "
                                                  "installed whole?): {}",
                                                  file.string(), id, sha.error().message));
                const std::string scope = id.ends_with("_global") ? "global" : "floor";
                known = found.emplace(id, CompanionPlugin{id, file.string(), scope, *sha}).first;
            }
            spec.companions.push_back(known->second);
        }
    }
    return {};
}

}  // namespace acetate::harness
