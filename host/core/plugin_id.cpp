#include "core/plugin_id.hpp"

#include <regex>

namespace acetate {

bool is_reverse_dns(const std::string& id) {
    static const std::regex pattern("[a-z][a-z0-9_-]*(\\.[a-z][a-z0-9_-]*)+");
    return std::regex_match(id, pattern);
}

}  // namespace acetate
