#pragma once
// What a plugin id looks like: a reverse-DNS name ("com.example.glow"). The loader checks a
// descriptor's id with it and the registry every entry's, so the rule lives below both.

#include <string>

namespace acetate {

// Lower-case labels of letters, digits, '_' and '-', each starting with a letter, at least
// two of them joined by '.'.
bool is_reverse_dns(const std::string& id);

}  // namespace acetate
