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
#include "core/plugin_id.hpp"
#include "core/sha256.hpp"
#include "core/strict_json.hpp"
#include "registry_fields.hpp"

namespace acetate {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using nlohmann::ordered_json;
using namespace registry_fields;

constexpr std::array<const char*, 5> kStageNames = {"UNVALIDATED", "REVIEWED", "ALPHA_TESTED",
                                                    "INTEGRATED", "VALIDATED"};

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

// A sign-off's own fields, before it is recorded: who, when, and the source it is for.
Result<void> check_sign_off(std::string_view id, std::string_view version, const char* what,
                            const SignOff& s, std::string_view source_digest) {
    if (is_blank(s.by))
        return refused(
            id, version,
            fmt::format("{} refused: the {}'s name is empty (a sign-off says who "
                        "signed)",
                        what, std::string_view(what) == "review" ? "reviewer" : "maintainer"));
    if (!is_timestamp(s.at))
        return refused(id, version,
                       fmt::format("{} refused: time \"{}\" is not ISO-8601 UTC", what, s.at));
    if (s.source_digest != source_digest)
        return refused(id, version,
                       fmt::format("{} refused: it signs source {}, the plugin's is {}", what,
                                   short_hash(s.source_digest), short_hash(source_digest)));
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
        if (!s && e->distrusted.count(what)) return e->distrusted.at(what);
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
    std::erase_if(e.waivers, [&](const Waiver& w) { return w.source_digest != source; });
    e.binary_sha256 = binary;
    e.source_digest = source;
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
    return record_review(id, version, binary_sha256, source_digest,
                         SignOff{std::string(reviewer), clock_(), std::string(notes),
                                 std::string(source_digest), ""});
}

Result<void> Registry::record_review(std::string_view id, std::string_view version,
                                     std::string_view binary_sha256, std::string_view source_digest,
                                     SignOff review) {
    ACETATE_TRY(check_identity(id, version, binary_sha256, source_digest));
    ACETATE_TRY(check_sign_off(id, version, "review", review, source_digest));
    RegistryEntry& e = entry_for(id, version);
    rebind(e, binary_sha256, source_digest);
    e.review = std::move(review);
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
    const RegistryEntry* existing = find(id, version);
    if (existing && existing->stage() == ValidationStage::Validated)
        return refused(id, version, "promotion refused: it is already VALIDATED");
    return promote(id, version,
                   SignOff{std::string(by), clock_(), std::string(notes),
                           existing ? existing->source_digest : "", ""});
}

Result<void> Registry::promote(std::string_view id, std::string_view version, SignOff promotion) {
    const RegistryEntry* existing = find(id, version);
    if (!existing)
        return refused(id, version, "promotion refused: the registry has no record of it");
    ACETATE_TRY(check_sign_off(id, version, "promotion", promotion, existing->source_digest));
    // A promotion already there is replaced: the caller has found it untrusted (its signature
    // does not hold) and signs a new one.
    const ValidationStage held = existing->stage();
    if (held != ValidationStage::Integrated && held != ValidationStage::Validated)
        return refused(id, version,
                       fmt::format("promotion refused: only an INTEGRATED plugin is promoted; it "
                                   "is {} ({})",
                                   to_string(held),
                                   first_missing_record(existing, existing->binary_sha256,
                                                        existing->source_digest)));
    const std::string today = clock_().substr(0, 10);
    for (const Waiver& w : existing->waivers)
        if (w.expired(today))
            return refused(id, version,
                           fmt::format("promotion refused: the waiver of \"{}\" expired on {} "
                                       "(by {}: {}); renew it or fix the plugin",
                                       w.check, w.until, w.by, w.reason));
    const bool strictness_waived =
        std::any_of(existing->waivers.begin(), existing->waivers.end(),
                    [](const Waiver& w) { return w.check == kStrictnessWaiver; });
    for (const auto* ev : {&existing->alpha_tested, &existing->integrated})
        if (*ev && (*ev)->strictness > 0 && (*ev)->strictness < kDefaultStrictness &&
            !strictness_waived)
            return refused(id, version,
                           fmt::format("promotion refused: its evidence was taken at strictness "
                                       "{}, below the default {}; validate again at {} or more, "
                                       "or waive \"{}\" saying why",
                                       (*ev)->strictness, kDefaultStrictness, kDefaultStrictness,
                                       kStrictnessWaiver));
    RegistryEntry& e = entry_for(id, version);
    e.promotion = std::move(promotion);
    return {};
}

Result<void> Registry::waive(std::string_view id, std::string_view version,
                             std::string_view binary_sha256, std::string_view source_digest,
                             Waiver waiver) {
    ACETATE_TRY(check_identity(id, version, binary_sha256, source_digest));
    if (is_blank(waiver.check)) return refused(id, version, "waiver refused: no check named");
    if (is_blank(waiver.reason))
        return refused(id, version, "waiver refused: the reason is empty (a waiver says why)");
    if (is_blank(waiver.by))
        return refused(id, version, "waiver refused: the maintainer's name is empty");
    const std::string now = clock_();
    if (!is_day(waiver.until))
        return refused(id, version,
                       fmt::format("waiver refused: --until \"{}\" is not a day "
                                   "(YYYY-MM-DD)",
                                   waiver.until));
    if (waiver.expired(now.substr(0, 10)))
        return refused(id, version,
                       fmt::format("waiver refused: --until {} is already past", waiver.until));
    const RegistryEntry* existing = find(id, version);
    const ValidationStage held =
        existing ? existing->stage_for(binary_sha256, source_digest) : ValidationStage::Unvalidated;
    if (held == ValidationStage::Unvalidated)
        return refused(id, version,
                       fmt::format("waiver refused: it is UNVALIDATED for this source ({}); a "
                                   "waiver is granted on reviewed code",
                                   first_missing_record(existing, binary_sha256, source_digest)));
    RegistryEntry& e = entry_for(id, version);
    waiver.at = now;
    waiver.source_digest = source_digest;
    std::erase_if(e.waivers, [&](const Waiver& w) { return w.check == waiver.check; });
    e.waivers.push_back(std::move(waiver));
    std::sort(e.waivers.begin(), e.waivers.end(),
              [](const Waiver& a, const Waiver& b) { return a.check < b.check; });
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

Result<Registry> Registry::load(const fs::path& file) {
    auto bytes = read_input_file_if_exists(file, kMaxRegistryFileBytes, "a registry");
    if (!bytes) return bytes.error();
    if (!bytes.value()) return Registry();
    return parse(*bytes.value(), file.string());
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

std::string utc_now_iso8601() {
    const std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    char buffer[32];
    std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", &utc);
    return buffer;
}

}  // namespace acetate
