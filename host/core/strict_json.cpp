#include "core/strict_json.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/input_file.hpp"
#include "core/json_fields.hpp"

namespace acetate {
namespace {

using json = nlohmann::json;
// Paths and quoting as the field reader writes them, so a duplicate reads like any field error.
using json_fields::element;
using json_fields::field;
using json_fields::json_quoted;

// A parser callback that remembers the first key written twice in one object, and where.
class DuplicateKeyFinder {
  public:
    bool on_event(json::parse_event_t event, const json& parsed) {
        using E = json::parse_event_t;
        switch (event) {
            case E::object_start:
                stack_.push_back({true});
                break;
            case E::array_start:
                stack_.push_back({false});
                break;
            case E::key:
                on_key(parsed.get<std::string>());
                break;
            case E::object_end:
            case E::array_end:
                stack_.pop_back();
                element_done();
                break;
            case E::value:
                element_done();
                break;
        }
        return true;
    }
    const std::optional<std::pair<std::string, std::string>>& found() const { return found_; }

  private:
    struct Frame {
        bool object;
        std::set<std::string> keys{};
        std::string key{};
        size_t index = 0;
    };

    void on_key(const std::string& key) {
        Frame& top = stack_.back();
        top.key = key;
        if (!top.keys.insert(key).second && !found_) found_.emplace(container_path(), key);
    }
    void element_done() {
        if (!stack_.empty() && !stack_.back().object) ++stack_.back().index;
    }
    // The path of the innermost container: every enclosing frame's current child.
    std::string container_path() const {
        std::string path;
        for (size_t i = 0; i + 1 < stack_.size(); ++i)
            path = stack_[i].object ? field(path, stack_[i].key) : element(path, stack_[i].index);
        return path;
    }

    std::vector<Frame> stack_;
    std::optional<std::pair<std::string, std::string>> found_;
};

// nlohmann's message starts with "[json.exception.parse_error.101] "; the id means nothing to
// the file's author, the line and column do. A lexer error quotes the token it last read
// ("; last read: '...'"), which for an unterminated string is the rest of the file: dropped,
// keeping what was expected after it.
std::string one_line_parse_message(const std::string& what) {
    std::string message = what;
    if (message.rfind("[json.exception.", 0) == 0) {
        const size_t end = message.find("] ");
        if (end != std::string::npos) message.erase(0, end + 2);
    }
    if (const size_t quote = message.find("; last read: '"); quote != std::string::npos) {
        const size_t expected = message.rfind("'; expected ");
        message.erase(quote, expected != std::string::npos && expected > quote
                                 ? expected + 1 - quote
                                 : std::string::npos);
    }
    std::replace(message.begin(), message.end(), '\n', ' ');
    std::replace(message.begin(), message.end(), '\r', ' ');
    return message;
}

}  // namespace

Result<json> parse_json_strict(std::string_view text, std::string_view label) {
    DuplicateKeyFinder duplicates;
    json root;
    try {
        root = json::parse(text.begin(), text.end(),
                           [&](int, json::parse_event_t event, json& parsed) {
                               return duplicates.on_event(event, parsed);
                           });
    } catch (const json::exception& e) {
        // parse_error carries the line and column; out_of_range is a number too large to hold.
        return make_error(ErrorCode::InvalidInput, fmt::format("{}: malformed JSON: {}", label,
                                                               one_line_parse_message(e.what())));
    }
    if (const auto& dup = duplicates.found())
        return json_fields::to_error({dup->first, "duplicate field " + json_quoted(dup->second)},
                                     label);
    return root;
}

Result<json> read_json_file(const std::filesystem::path& file, std::uint64_t max_bytes,
                            std::string_view what) {
    auto text = read_input_file(file, max_bytes, what);
    if (!text) return text.error();
    return parse_json_strict(text.value(), file.string());
}

}  // namespace acetate
