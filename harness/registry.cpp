#include "registry.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <ctime>
#include <limits>
#include <nlohmann/json.hpp>
#include <regex>

#include "core/atomic_file.hpp"
#include "core/input_file.hpp"
#include "core/sha256.hpp"
#include "core/strict_json.hpp"
#include "json_fields.hpp"
#include "plugins/effect_descriptor.hpp"

namespace acetate {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using nlohmann::ordered_json;

constexpr std::array<const char*, 5> kStageNames = {"UNVALIDATED", "REVIEWED", "ALPHA_TESTED",
                                                    "INTEGRATED", "VALIDATED"};
// Verdicts that make a run fail; evidence records passing runs only.
constexpr std::array<const char*, 4> kFailingVerdicts = {"FAIL", "FLAKY", "CRASH", "TIMEOUT"};

// ---- small checks and formatting ---------------------------------------------------------

bool is_hex64(std::string_view s) {
    return s.size() == 64 && std::all_of(s.begin(), s.end(), [](char c) {
               return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
           });
}

// "MAJOR.MINOR.PATCH", each a decimal uint32 without sign.
std::optional<std::array<uint32_t, 3>> parse_version(std::string_view s) {
    std::array<uint32_t, 3> out{};
    for (size_t i = 0; i < 3; ++i) {
        const size_t dot = i < 2 ? s.find('.') : s.size();
        if (dot == std::string_view::npos || dot == 0) return std::nullopt;
        const std::string_view part = s.substr(0, dot);
        auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), out[i]);
        if (ec != std::errc() || end != part.data() + part.size()) return std::nullopt;
        s.remove_prefix(std::min(s.size(), dot + 1));
        if (i < 2 && s.empty()) return std::nullopt;
    }
    return out;
}

bool is_timestamp(const std::string& s) {
    static const std::regex pattern(
        "\\d{4}-(0[1-9]|1[0-2])-(0[1-9]|[12]\\d|3[01])T([01]\\d|2[0-3]):[0-5]\\d:[0-5]\\dZ");
    return std::regex_match(s, pattern);
}

bool is_blank(std::string_view s) {
    return std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isspace(c); });
}

std::string short_hash(std::string_view hash) {
    return std::string(hash.substr(0, 12));
}

std::string plugin_name(std::string_view id, std::string_view version) {
    return fmt::format("{} {}", id, version);
}

Error refused(std::string_view id, std::string_view version, const std::string& what) {
    return make_error(ErrorCode::InvalidInput,
                      fmt::format("{}: {}", plugin_name(id, version), what));
}

Error io_error(const fs::path& file, std::string_view what, int err) {
    return make_error(ErrorCode::Io,
                      fmt::format("{}: {}: {}", file.string(), what, std::strerror(err)));
}

ValidationStage next(ValidationStage s) {
    return ValidationStage(int(s) + 1);
}

// The shapes every operation checks before touching an entry.
Result<void> check_identity(std::string_view id, std::string_view version,
                            std::string_view binary_sha256, std::string_view source_digest) {
    if (!is_reverse_dns(std::string(id)))
        return refused(id, version, "the plugin id is not reverse-DNS (e.g. org.acetate.bloom)");
    if (!parse_version(version))
        return refused(id, version, "the version is not MAJOR.MINOR.PATCH");
    if (!is_hex64(binary_sha256))
        return refused(
            id, version,
            fmt::format("binary SHA-256 \"{}\" is not 64 lowercase hex digits", binary_sha256));
    if (source_digest.empty())
        return refused(id, version,
                       "the plugin has no source digest (built without "
                       "acetate_add_effect); sign-offs bind to one");
    if (!is_hex64(source_digest))
        return refused(
            id, version,
            fmt::format("source digest \"{}\" is not 64 lowercase hex digits", source_digest));
    return {};
}

// Why `e` does not reach the stage after the one it holds for this binary and source.
std::string first_missing_record(const RegistryEntry* e, std::string_view binary,
                                 std::string_view source) {
    if (!e) return "the registry has no record of it";
    auto evidence_gap = [&](const char* stage, const std::optional<StageEvidence>& ev) {
        std::string out = fmt::format("no {} evidence for binary {}", stage, short_hash(binary));
        if (ev) out += fmt::format(" (recorded for {})", short_hash(ev->binary_sha256));
        return out;
    };
    auto sign_off_gap = [&](const char* what, const std::optional<SignOff>& s) {
        std::string out = fmt::format("no {} sign-off for source {}", what, short_hash(source));
        if (s) out += fmt::format(" (signed for {})", short_hash(s->source_digest));
        return out;
    };
    switch (e->stage_for(binary, source)) {
        case ValidationStage::Unvalidated:
            return sign_off_gap("review", e->review);
        case ValidationStage::Reviewed:
            return evidence_gap("ALPHA_TESTED", e->alpha_tested);
        case ValidationStage::AlphaTested:
            return evidence_gap("INTEGRATED", e->integrated);
        case ValidationStage::Integrated:
            return sign_off_gap("promotion", e->promotion);
        case ValidationStage::Validated:
            break;
    }
    return "";
}

// The entry of `id` (any id when empty) recorded with this binary that holds the highest
// stage; null when none was.
const RegistryEntry* best_for_binary(const std::vector<RegistryEntry>& entries, std::string_view id,
                                     std::string_view binary) {
    const RegistryEntry* best = nullptr;
    for (const RegistryEntry& e : entries)
        if ((id.empty() || e.id == id) && e.binary_sha256 == binary &&
            (!best || int(e.stage()) > int(best->stage())))
            best = &e;
    return best;
}

// Moves `e` to a new binary and source: records bound to other ones no longer hold.
void rebind(RegistryEntry& e, std::string_view binary, std::string_view source) {
    if (e.review && e.review->source_digest != source) e.review.reset();
    if (e.promotion && e.promotion->source_digest != source) e.promotion.reset();
    if (e.alpha_tested && e.alpha_tested->binary_sha256 != binary) e.alpha_tested.reset();
    if (e.integrated && e.integrated->binary_sha256 != binary) e.integrated.reset();
    e.binary_sha256 = binary;
    e.source_digest = source;
}

bool entry_less(const RegistryEntry& a, const RegistryEntry& b) {
    if (a.id != b.id) return a.id < b.id;
    return parse_version(a.version) < parse_version(b.version);
}

// ---- file helpers ---------------------------------------------------------------------------

// An exclusive flock held until destruction (closing the descriptor releases it).
class ExclusiveLock {
  public:
    ExclusiveLock() = default;
    ExclusiveLock(const ExclusiveLock&) = delete;
    ExclusiveLock& operator=(const ExclusiveLock&) = delete;
    ~ExclusiveLock() {
        if (fd_ >= 0) ::close(fd_);
    }
    Result<void> acquire(const fs::path& lock_file) {
        fd_ = ::open(lock_file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
        if (fd_ < 0) return io_error(lock_file, "cannot open the lock file", errno);
        while (::flock(fd_, LOCK_EX) != 0)
            if (errno != EINTR) return io_error(lock_file, "cannot lock", errno);
        return {};
    }

  private:
    int fd_ = -1;
};

// ---- JSON reading -------------------------------------------------------------------------
// Field errors (json_fields.hpp) are caught in Registry::parse.
using namespace json_fields;

std::string text(const json& j, const std::string& path, std::string_view key) {
    const json& v = j.at(std::string(key));
    if (!v.is_string())
        fail(field(path, key), fmt::format("must be a string, found {}", v.type_name()));
    return v.get<std::string>();
}

std::string nonempty(const json& j, const std::string& path, std::string_view key) {
    std::string s = text(j, path, key);
    if (is_blank(s)) fail(field(path, key), "must not be empty");
    return s;
}

std::string hex64(const json& j, const std::string& path, std::string_view key) {
    std::string s = text(j, path, key);
    if (!is_hex64(s))
        fail(field(path, key), fmt::format("\"{}\" is not 64 lowercase hex digits", s));
    return s;
}

std::string timestamp(const json& j, const std::string& path, std::string_view key) {
    std::string s = text(j, path, key);
    if (!is_timestamp(s))
        fail(field(path, key), fmt::format("\"{}\" is not ISO-8601 UTC (YYYY-MM-DDTHH:MM:SSZ)", s));
    return s;
}

SignOff read_sign_off(const json& j, const std::string& path) {
    expect_object(j, path, {"by", "at", "notes", "source_digest"});
    return SignOff{nonempty(j, path, "by"), timestamp(j, path, "at"), text(j, path, "notes"),
                   hex64(j, path, "source_digest")};
}

StageEvidence read_evidence(const json& j, const std::string& path) {
    expect_object(j, path,
                  {"at", "harness_version", "summary", "counts", "report", "binary_sha256"});
    StageEvidence ev{timestamp(j, path, "at"), nonempty(j, path, "harness_version"),
                     text(j, path, "summary"), {},
                     text(j, path, "report"),  hex64(j, path, "binary_sha256")};
    const std::string counts_path = field(path, "counts");
    const json& counts = j.at("counts");
    if (!counts.is_object()) fail(counts_path, "must be an object of verdict: count");
    for (const auto& [verdict, n] : counts.items()) {
        if (verdict.empty()) fail(counts_path, "a verdict name is empty");
        if (!n.is_number_unsigned())
            fail(field(counts_path, verdict), "must be a non-negative integer");
        ev.counts[verdict] = n.get<uint64_t>();
    }
    for (const char* bad : kFailingVerdicts)
        if (ev.counts.count(bad) && ev.counts.at(bad) > 0)
            fail(field(counts_path, bad), "evidence records passing runs only");
    return ev;
}

RegistryEntry read_entry(const json& j, const std::string& path) {
    if (!j.is_object()) fail(path, fmt::format("must be an object, found {}", j.type_name()));
    expect_object(j, path, {"id", "version", "stage", "binary_sha256", "source_digest"},
                  {"review", "alpha_tested", "integrated", "promotion"});

    RegistryEntry e;
    e.id = text(j, path, "id");
    if (!is_reverse_dns(e.id))
        fail(field(path, "id"), fmt::format("\"{}\" is not reverse-DNS", e.id));
    e.version = text(j, path, "version");
    if (!parse_version(e.version))
        fail(field(path, "version"), fmt::format("\"{}\" is not MAJOR.MINOR.PATCH", e.version));
    e.binary_sha256 = hex64(j, path, "binary_sha256");
    e.source_digest = hex64(j, path, "source_digest");
    if (j.contains("review")) e.review = read_sign_off(j["review"], field(path, "review"));
    if (j.contains("promotion"))
        e.promotion = read_sign_off(j["promotion"], field(path, "promotion"));
    if (j.contains("alpha_tested"))
        e.alpha_tested = read_evidence(j["alpha_tested"], field(path, "alpha_tested"));
    if (j.contains("integrated"))
        e.integrated = read_evidence(j["integrated"], field(path, "integrated"));

    // Every record binds to the entry's binary and source, and none skips a stage: that is
    // what the operations produce, so anything else was edited by hand.
    auto bound = [&](const char* key, const std::string& got, const std::string& want,
                     const char* what) {
        if (got != want)
            fail(field(field(path, key), what),
                 fmt::format("{} is not the entry's {} {}", short_hash(got), what,
                             short_hash(want)));
    };
    if (e.review) bound("review", e.review->source_digest, e.source_digest, "source_digest");
    if (e.promotion)
        bound("promotion", e.promotion->source_digest, e.source_digest, "source_digest");
    if (e.alpha_tested)
        bound("alpha_tested", e.alpha_tested->binary_sha256, e.binary_sha256, "binary_sha256");
    if (e.integrated)
        bound("integrated", e.integrated->binary_sha256, e.binary_sha256, "binary_sha256");
    if ((e.alpha_tested || e.promotion) && !e.review)
        fail(path, "has later records but no review (stages are never skipped)");
    if (e.integrated && !e.alpha_tested)
        fail(field(path, "integrated"), "present without alpha_tested (stages are never skipped)");

    const std::string stage = text(j, path, "stage");
    if (stage != to_string(e.stage()))
        fail(field(path, "stage"),
             fmt::format("says {} but its records support {}", stage, to_string(e.stage())));
    return e;
}

// ---- JSON writing ---------------------------------------------------------------------------

ordered_json write_sign_off(const SignOff& s) {
    return ordered_json{
        {"by", s.by}, {"at", s.at}, {"notes", s.notes}, {"source_digest", s.source_digest}};
}

ordered_json write_evidence(const StageEvidence& ev) {
    ordered_json counts = ordered_json::object();
    for (const auto& [verdict, n] : ev.counts) counts[verdict] = n;
    return ordered_json{{"at", ev.at},           {"harness_version", ev.harness_version},
                        {"summary", ev.summary}, {"counts", counts},
                        {"report", ev.report},   {"binary_sha256", ev.binary_sha256}};
}

// ---- Markdown -------------------------------------------------------------------------------

// One line, safe inside a table cell.
std::string cell(std::string_view s) {
    std::string out;
    for (char c : s) {
        if (c == '|')
            out += "\\|";
        else if (c == '\n' || c == '\r')
            out += ' ';
        else
            out += c;
    }
    return out;
}

std::string who_when(const std::optional<SignOff>& s) {
    return s ? cell(fmt::format("{}, {}", s->by, s->at)) : "—";
}

std::string when_harness(const std::optional<StageEvidence>& ev) {
    return ev ? cell(fmt::format("{} (harness {})", ev->at, ev->harness_version)) : "—";
}

std::string counts_text(const StageEvidence& ev) {
    std::vector<std::string> parts;
    for (const auto& [verdict, n] : ev.counts) parts.push_back(fmt::format("{} {}", n, verdict));
    return parts.empty() ? "no counts" : fmt::format("{}", fmt::join(parts, ", "));
}

}  // namespace

// ---- stages -------------------------------------------------------------------------------

const char* to_string(ValidationStage stage) {
    return kStageNames[size_t(stage)];
}

std::optional<ValidationStage> parse_validation_stage(std::string_view name) {
    std::string canonical;
    for (char c : name) canonical += c == '-' ? '_' : char(std::toupper((unsigned char)c));
    for (size_t i = 0; i < kStageNames.size(); ++i)
        if (canonical == kStageNames[i]) return ValidationStage(i);
    return std::nullopt;
}

ValidationStage RegistryEntry::stage_for(std::string_view binary, std::string_view source) const {
    if (!review || review->source_digest != source) return ValidationStage::Unvalidated;
    if (!alpha_tested || alpha_tested->binary_sha256 != binary) return ValidationStage::Reviewed;
    if (!integrated || integrated->binary_sha256 != binary) return ValidationStage::AlphaTested;
    if (!promotion || promotion->source_digest != source) return ValidationStage::Integrated;
    return ValidationStage::Validated;
}

// ---- Registry -----------------------------------------------------------------------------

Registry::Registry() : clock_(utc_now_iso8601) {}

const RegistryEntry* Registry::find(std::string_view id, std::string_view version) const {
    for (const RegistryEntry& e : entries_)
        if (e.id == id && e.version == version) return &e;
    return nullptr;
}

RegistryEntry& Registry::entry_for(std::string_view id, std::string_view version) {
    for (RegistryEntry& e : entries_)
        if (e.id == id && e.version == version) return e;
    RegistryEntry fresh;
    fresh.id = id;
    fresh.version = version;
    auto at = std::upper_bound(entries_.begin(), entries_.end(), fresh, entry_less);
    return *entries_.insert(at, std::move(fresh));
}

Result<void> Registry::record_review(std::string_view id, std::string_view version,
                                     std::string_view binary_sha256, std::string_view source_digest,
                                     std::string_view reviewer, std::string_view notes) {
    ACETATE_TRY(check_identity(id, version, binary_sha256, source_digest));
    if (is_blank(reviewer))
        return refused(id, version,
                       "review refused: the reviewer's name is empty (a sign-off says who "
                       "signed)");
    RegistryEntry& e = entry_for(id, version);
    rebind(e, binary_sha256, source_digest);
    e.review =
        SignOff{std::string(reviewer), clock_(), std::string(notes), std::string(source_digest)};
    return {};
}

Result<void> Registry::record_evidence(std::string_view id, std::string_view version,
                                       std::string_view binary_sha256,
                                       std::string_view source_digest, ValidationStage stage,
                                       StageEvidence evidence) {
    if (stage != ValidationStage::AlphaTested && stage != ValidationStage::Integrated)
        return refused(id, version,
                       fmt::format("evidence is recorded for ALPHA_TESTED or INTEGRATED only, "
                                   "not {}",
                                   to_string(stage)));
    ACETATE_TRY(check_identity(id, version, binary_sha256, source_digest));
    const char* name = to_string(stage);
    if (is_blank(evidence.harness_version))
        return refused(id, version, fmt::format("{} evidence refused: no harness version", name));
    for (const char* bad : kFailingVerdicts)
        if (evidence.counts.count(bad) && evidence.counts.at(bad) > 0)
            return refused(id, version,
                           fmt::format("{} evidence refused: the run has {} {}; evidence "
                                       "records passing runs only",
                                       name, evidence.counts.at(bad), bad));
    if (evidence.at.empty()) evidence.at = clock_();
    if (!is_timestamp(evidence.at))
        return refused(
            id, version,
            fmt::format("{} evidence refused: time \"{}\" is not ISO-8601 UTC", name, evidence.at));

    const RegistryEntry* existing = find(id, version);
    const ValidationStage held =
        existing ? existing->stage_for(binary_sha256, source_digest) : ValidationStage::Unvalidated;
    if (int(held) < int(stage) - 1)
        return refused(id, version,
                       fmt::format("{} evidence refused: it is {} and stages are never skipped; "
                                   "{} comes first ({})",
                                   name, to_string(held), to_string(next(held)),
                                   first_missing_record(existing, binary_sha256, source_digest)));

    RegistryEntry& e = entry_for(id, version);
    rebind(e, binary_sha256, source_digest);
    evidence.binary_sha256 = binary_sha256;
    (stage == ValidationStage::AlphaTested ? e.alpha_tested : e.integrated) = std::move(evidence);
    return {};
}

Result<void> Registry::promote(std::string_view id, std::string_view version, std::string_view by,
                               std::string_view notes) {
    if (is_blank(by))
        return refused(id, version,
                       "promotion refused: the maintainer's name is empty (a sign-off says "
                       "who signed)");
    const RegistryEntry* existing = find(id, version);
    if (!existing)
        return refused(id, version, "promotion refused: the registry has no record of it");
    const ValidationStage held = existing->stage();
    if (held == ValidationStage::Validated)
        return refused(id, version, "promotion refused: it is already VALIDATED");
    if (held != ValidationStage::Integrated)
        return refused(id, version,
                       fmt::format("promotion refused: only an INTEGRATED plugin is promoted; it "
                                   "is {} ({})",
                                   to_string(held),
                                   first_missing_record(existing, existing->binary_sha256,
                                                        existing->source_digest)));
    RegistryEntry& e = entry_for(id, version);
    e.promotion = SignOff{std::string(by), clock_(), std::string(notes), e.source_digest};
    return {};
}

ValidationStage Registry::effective_stage(std::string_view id, std::string_view version,
                                          std::string_view binary_sha256,
                                          std::string_view source_digest) const {
    const RegistryEntry* e = find(id, version);
    return e ? e->stage_for(binary_sha256, source_digest) : ValidationStage::Unvalidated;
}

bool Registry::is_validated(std::string_view id, std::string_view binary_sha256) const {
    return std::any_of(entries_.begin(), entries_.end(), [&](const RegistryEntry& e) {
        return e.id == id && e.binary_sha256 == binary_sha256 &&
               e.stage() == ValidationStage::Validated;
    });
}

Result<void> Registry::require_validated(std::string_view id, std::string_view version,
                                         std::string_view binary_sha256,
                                         std::string_view source_digest) const {
    const ValidationStage held = effective_stage(id, version, binary_sha256, source_digest);
    if (held == ValidationStage::Validated) return {};
    return refused(
        id, version,
        fmt::format("is {}, not VALIDATED: {}", to_string(held),
                    first_missing_record(find(id, version), binary_sha256, source_digest)));
}

ValidationStage Registry::binary_stage(std::string_view id, std::string_view binary_sha256) const {
    const RegistryEntry* e = best_for_binary(entries_, id, binary_sha256);
    return e ? e->stage() : ValidationStage::Unvalidated;
}

std::string Registry::explain(std::string_view id, std::string_view binary_sha256) const {
    if (const RegistryEntry* e = best_for_binary(entries_, id, binary_sha256)) {
        const ValidationStage held = e->stage();
        std::string out = fmt::format("{} is {} for this binary", plugin_name(e->id, e->version),
                                      to_string(held));
        if (held != ValidationStage::Validated)
            out += ": " + first_missing_record(e, binary_sha256, e->source_digest);
        return out;
    }
    if (id.empty()) return "this binary is UNVALIDATED: no record of it";
    std::vector<std::string> others;
    for (const RegistryEntry& e : entries_)
        if (e.id == id)
            others.push_back(fmt::format("{} {} for {}", e.version, to_string(e.stage()),
                                         short_hash(e.binary_sha256)));
    if (others.empty()) return fmt::format("{} is UNVALIDATED: no record of it", id);
    return fmt::format("{} is UNVALIDATED for this binary: recorded only for other binaries: {}",
                       id, fmt::join(others, ", "));
}

// ---- the file -------------------------------------------------------------------------------

Result<Registry> Registry::parse(std::string_view json_text, std::string_view name) {
    // Strict: a key written twice (a second binary_sha256 in an entry, say) is refused, so
    // what a reviewer reads in the file is what the host uses.
    auto parsed = parse_json_strict(json_text, name);
    if (!parsed) return parsed.error();
    const json& doc = parsed.value();
    Registry registry;
    try {
        expect_object(doc, "", {"format", "plugins"});
        if (const std::string format = text(doc, "", "format"); format != kFormat)
            fail("format", fmt::format("\"{}\" is not \"{}\"", format, kFormat));
        const json& plugins = doc["plugins"];
        if (!plugins.is_array()) fail("plugins", "must be an array");
        for (size_t i = 0; i < plugins.size(); ++i) {
            const std::string path = fmt::format("plugins[{}]", i);
            RegistryEntry e = read_entry(plugins[i], path);
            if (registry.find(e.id, e.version))
                fail(path, fmt::format("{} appears twice", plugin_name(e.id, e.version)));
            registry.entries_.push_back(std::move(e));
        }
    } catch (const JsonFieldError& e) {
        const std::string where = e.path.empty() ? "" : e.path + ": ";
        return make_error(ErrorCode::InvalidInput, fmt::format("{}: {}{}", name, where, e.what));
    }
    std::sort(registry.entries_.begin(), registry.entries_.end(), entry_less);
    return registry;
}

Result<Registry> Registry::load(const fs::path& file) {
    auto bytes = read_input_file_if_exists(file, kMaxRegistryFileBytes, "a registry");
    if (!bytes) return bytes.error();
    if (!bytes.value()) return Registry();
    return parse(*bytes.value(), file.string());
}

std::string Registry::to_json() const {
    ordered_json plugins = ordered_json::array();
    for (const RegistryEntry& e : entries_) {
        ordered_json j = {{"id", e.id},
                          {"version", e.version},
                          {"stage", to_string(e.stage())},
                          {"binary_sha256", e.binary_sha256},
                          {"source_digest", e.source_digest}};
        if (e.review) j["review"] = write_sign_off(*e.review);
        if (e.alpha_tested) j["alpha_tested"] = write_evidence(*e.alpha_tested);
        if (e.integrated) j["integrated"] = write_evidence(*e.integrated);
        if (e.promotion) j["promotion"] = write_sign_off(*e.promotion);
        plugins.push_back(std::move(j));
    }
    const ordered_json doc = {{"format", std::string(kFormat)}, {"plugins", plugins}};
    return doc.dump(2) + "\n";
}

Result<void> Registry::save(const fs::path& file) const {
    return write_file_atomically(file, to_json());
}

Result<void> Registry::update(const fs::path& file,
                              const std::function<Result<void>(Registry&)>& change,
                              const fs::path& markdown) {
    if (file.has_parent_path()) {
        std::error_code ec;
        fs::create_directories(file.parent_path(), ec);
        if (ec) return io_error(file.parent_path(), "cannot create the folder", ec.value());
    }
    fs::path lock_file = file;
    lock_file += ".lock";
    ExclusiveLock lock;
    ACETATE_TRY(lock.acquire(lock_file));
    // A writer killed where O_TMPFILE is unavailable leaves a named temporary: clear those.
    remove_dead_writers_temporaries(file);
    if (!markdown.empty()) remove_dead_writers_temporaries(markdown);

    auto loaded = load(file);
    if (!loaded) return loaded.error();
    Registry registry = std::move(loaded).value();
    ACETATE_TRY(change(registry));
    ACETATE_TRY(registry.save(file));
    if (!markdown.empty())
        ACETATE_TRY(write_registry_markdown(registry, markdown, file.filename().string()));
    return {};
}

// ---- VALIDATION-REGISTRY.md -----------------------------------------------------------------

std::string render_registry_markdown(const Registry& registry, std::string_view source_name) {
    std::string out = fmt::format(
        "# Validation registry\n\n"
        "Generated from `{}` by acetate-harness; do not edit by hand. Stages: UNVALIDATED → "
        "REVIEWED → ALPHA_TESTED → INTEGRATED → VALIDATED, never skipped; what each promises is "
        "in docs/registry.md. Sign-offs bind to the source digest, evidence to the binary's "
        "SHA-256 (both shortened to 12 digits here).\n\n",
        source_name);
    if (registry.entries().empty()) return out + "No plugins recorded yet.\n";

    out +=
        "| Plugin | Version | Stage | Binary SHA-256 | Source digest | Reviewed | "
        "Alpha-tested | Integrated | Promoted |\n"
        "|---|---|---|---|---|---|---|---|---|\n";
    for (const RegistryEntry& e : registry.entries())
        out += fmt::format("| `{}` | {} | **{}** | `{}` | `{}` | {} | {} | {} | {} |\n", e.id,
                           e.version, to_string(e.stage()), short_hash(e.binary_sha256),
                           short_hash(e.source_digest), who_when(e.review),
                           when_harness(e.alpha_tested), when_harness(e.integrated),
                           who_when(e.promotion));

    for (const RegistryEntry& e : registry.entries()) {
        out += fmt::format("\n## {} {} — {}\n\n", e.id, e.version, to_string(e.stage()));
        out += fmt::format("- Binary SHA-256 `{}`, source digest `{}`\n", e.binary_sha256,
                           e.source_digest);
        auto sign_off = [&](const char* what, const std::optional<SignOff>& s) {
            if (s)
                out += cell(fmt::format("- {} by {} at {}: {}", what, s->by, s->at,
                                        s->notes.empty() ? "(no notes)" : s->notes)) +
                       "\n";
        };
        auto evidence = [&](const char* what, const std::optional<StageEvidence>& ev) {
            if (!ev) return;
            out +=
                cell(fmt::format("- {} at {}, harness {}: {}{}", what, ev->at, ev->harness_version,
                                 ev->summary.empty() ? "" : ev->summary + "; ", counts_text(*ev)));
            if (!ev->report.empty()) out += cell(fmt::format("; report `{}`", ev->report));
            out += "\n";
        };
        sign_off("Reviewed", e.review);
        evidence("Alpha-tested", e.alpha_tested);
        evidence("Integrated", e.integrated);
        sign_off("Promoted to VALIDATED", e.promotion);
    }
    return out;
}

Result<void> write_registry_markdown(const Registry& registry, const fs::path& file,
                                     std::string_view source_name) {
    return write_file_atomically(file, render_registry_markdown(registry, source_name));
}

Result<std::string> file_sha256(const fs::path& file) {
    // A plugin binary has no size limit of its own; it is still opened without blocking and
    // read only when it is a regular file.
    auto bytes = read_input_file(file, std::numeric_limits<std::uint64_t>::max(), "a plugin");
    if (!bytes) return bytes.error();
    return sha256_hex(bytes.value());
}

std::string utc_now_iso8601() {
    const std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    char buffer[32];
    std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", &utc);
    return buffer;
}

}  // namespace acetate
