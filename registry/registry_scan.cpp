#include "registry_scan.hpp"

#include <cstddef>

namespace acetate {
namespace {

// A cursor over JSON text; each skip_* returns false on anything malformed.
class Scanner {
  public:
    explicit Scanner(std::string_view text) : text_(text) {}

    void skip_space() {
        while (at_ < text_.size() && (text_[at_] == ' ' || text_[at_] == '\n' ||
                                      text_[at_] == '\r' || text_[at_] == '\t'))
            ++at_;
    }
    bool take(char c) {
        skip_space();
        if (at_ >= text_.size() || text_[at_] != c) return false;
        ++at_;
        return true;
    }
    bool peek(char c) {
        skip_space();
        return at_ < text_.size() && text_[at_] == c;
    }
    // A string; its raw contents (escapes left as written) in `raw`.
    bool string(std::string_view* raw = nullptr) {
        if (!take('"')) return false;
        const size_t begin = at_;
        while (at_ < text_.size()) {
            const char c = text_[at_];
            if (c == '\\') {
                at_ += 2;
                continue;
            }
            if (static_cast<unsigned char>(c) < 0x20) return false;
            if (c == '"') {
                if (raw) *raw = text_.substr(begin, at_ - begin);
                ++at_;
                return true;
            }
            ++at_;
        }
        return false;
    }
    // Any value. Nesting is counted, not recursed into, so a deep document cannot exhaust the
    // stack; strings are skipped as strings, so brackets inside them do not count.
    bool value() {
        skip_space();
        if (at_ >= text_.size()) return false;
        const char c = text_[at_];
        if (c == '"') return string();
        if (c != '{' && c != '[') return scalar();
        size_t depth = 0;
        while (at_ < text_.size()) {
            const char d = text_[at_];
            if (d == '"') {
                if (!string()) return false;
                continue;
            }
            if (d == '{' || d == '[') ++depth;
            if (d == '}' || d == ']') {
                if (depth == 0) return false;
                if (--depth == 0) {
                    ++at_;
                    return true;
                }
            }
            ++at_;
        }
        return false;
    }
    size_t position() {
        skip_space();
        return at_;
    }
    size_t here() const { return at_; }
    bool at_end() {
        skip_space();
        return at_ == text_.size();
    }
    std::string_view slice(size_t from, size_t to) const { return text_.substr(from, to - from); }

  private:
    // true, false, null or a number: the characters up to the next delimiter.
    bool scalar() {
        const size_t begin = at_;
        while (at_ < text_.size() && text_[at_] != ',' && text_[at_] != '}' && text_[at_] != ']' &&
               text_[at_] != ' ' && text_[at_] != '\n' && text_[at_] != '\r' && text_[at_] != '\t')
            ++at_;
        return at_ > begin;
    }

    std::string_view text_;
    size_t at_ = 0;
};

}  // namespace

std::optional<RegistryText> scan_registry(std::string_view json_text) {
    Scanner s(json_text);
    RegistryText out;
    bool seen_format = false, seen_plugins = false;
    if (!s.take('{')) return std::nullopt;
    if (!s.peek('}')) {
        do {
            std::string_view key;
            if (!s.string(&key) || !s.take(':')) return std::nullopt;
            if (key == "format" && !seen_format) {
                std::string_view format;
                if (!s.string(&format) || format.find('\\') != std::string_view::npos)
                    return std::nullopt;
                out.format = std::string(format);
                seen_format = true;
            } else if (key == "plugins" && !seen_plugins) {
                if (!s.take('[')) return std::nullopt;
                if (!s.peek(']')) {
                    do {
                        const size_t begin = s.position();
                        if (!s.peek('{') || !s.value()) return std::nullopt;
                        out.entries.push_back(s.slice(begin, s.here()));
                    } while (s.take(','));
                }
                if (!s.take(']')) return std::nullopt;
                seen_plugins = true;
            } else {
                return std::nullopt;  // another or a repeated member: the full reader says so
            }
        } while (s.take(','));
    }
    if (!s.take('}') || !s.at_end() || !seen_format || !seen_plugins) return std::nullopt;
    return out;
}

}  // namespace acetate
