// The registry's file format, acetate-registry/1 (docs/registry.md, "The file"): reading with
// errors that name the field path, and writing in a stable order (the file is diffed).

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <nlohmann/json.hpp>
#include <set>

#include "core/json_fields.hpp"
#include "core/plugin_id.hpp"
#include "core/strict_json.hpp"
#include "registry.hpp"
#include "registry_fields.hpp"
#include "registry_scan.hpp"

namespace acetate {
namespace {

using nlohmann::json;
using nlohmann::ordered_json;
using namespace registry_fields;

// ---- JSON reading -------------------------------------------------------------------------
// The one field reader (core/json_fields.hpp); its errors become a Result in Registry::parse.
using namespace json_fields;

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
    expect_object(j, path, {"by", "at", "notes", "source_digest"}, {"signature"});
    SignOff s{nonempty(j, path, "by"), timestamp(j, path, "at"), text(j, path, "notes"),
              hex64(j, path, "source_digest"), ""};
    // Read as it is: whether it holds is for verify_sign_offs to say, with the allowed
    // signers at hand (an unsigned sign-off still parses, and is not trusted).
    if (j.contains("signature")) s.signature = text(j, path, "signature");
    return s;
}

Waiver read_waiver(const json& j, const std::string& path) {
    expect_object(j, path, {"check", "reason", "by", "at", "until", "source_digest"});
    Waiver w{nonempty(j, path, "check"), nonempty(j, path, "reason"),
             nonempty(j, path, "by"),    timestamp(j, path, "at"),
             text(j, path, "until"),     hex64(j, path, "source_digest")};
    if (!is_day(w.until))
        fail(field(path, "until"), fmt::format("\"{}\" is not a day (YYYY-MM-DD)", w.until));
    return w;
}

StageEvidence read_evidence(const json& j, const std::string& path) {
    expect_object(j, path,
                  {"at", "harness_version", "summary", "counts", "report", "binary_sha256"},
                  {"strictness", "seed"});
    StageEvidence ev;
    ev.at = timestamp(j, path, "at");
    ev.harness_version = nonempty(j, path, "harness_version");
    ev.summary = text(j, path, "summary");
    ev.report = text(j, path, "report");
    ev.binary_sha256 = hex64(j, path, "binary_sha256");
    if (j.contains("strictness")) {
        const json& s = j["strictness"];
        if (!s.is_number_integer() || s.get<int64_t>() < 1 || s.get<int64_t>() > 10)
            fail(field(path, "strictness"), "must be an integer from 1 to 10");
        ev.strictness = s.get<int>();
    }
    if (j.contains("seed")) ev.seed = unsigned_integer(j, path, "seed");
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
    expect_object(j, path, {"id", "version", "stage", "binary_sha256", "source_digest"},
                  {"review", "alpha_tested", "integrated", "promotion", "waivers"});

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
    if (j.contains("waivers")) {
        const json& list = j["waivers"];
        if (!list.is_array()) fail(field(path, "waivers"), "must be an array");
        for (size_t i = 0; i < list.size(); ++i) {
            const std::string at = fmt::format("{}[{}]", field(path, "waivers"), i);
            Waiver w = read_waiver(list[i], at);
            if (w.source_digest != e.source_digest)
                fail(field(at, "source_digest"),
                     fmt::format("{} is not the entry's source_digest {}",
                                 short_hash(w.source_digest), short_hash(e.source_digest)));
            for (const Waiver& other : e.waivers)
                if (other.check == w.check)
                    fail(at, fmt::format("a second waiver of \"{}\"", w.check));
            e.waivers.push_back(std::move(w));
        }
        std::sort(e.waivers.begin(), e.waivers.end(),
                  [](const Waiver& a, const Waiver& b) { return a.check < b.check; });
    }

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
    ordered_json j{
        {"by", s.by}, {"at", s.at}, {"notes", s.notes}, {"source_digest", s.source_digest}};
    if (!s.signature.empty()) j["signature"] = s.signature;
    return j;
}

ordered_json write_evidence(const StageEvidence& ev) {
    ordered_json counts = ordered_json::object();
    for (const auto& [verdict, n] : ev.counts) counts[verdict] = n;
    ordered_json j{{"at", ev.at},           {"harness_version", ev.harness_version},
                   {"summary", ev.summary}, {"counts", counts},
                   {"report", ev.report},   {"binary_sha256", ev.binary_sha256}};
    if (ev.strictness > 0) j["strictness"] = ev.strictness;
    if (ev.seed) j["seed"] = *ev.seed;
    return j;
}

ordered_json write_waiver(const Waiver& w) {
    return ordered_json{{"check", w.check}, {"reason", w.reason},
                        {"by", w.by},       {"at", w.at},
                        {"until", w.until}, {"source_digest", w.source_digest}};
}

// Adds the entry read at `path`; a second entry of one plugin version is refused.
void add_once(std::vector<RegistryEntry>& entries,
              std::set<std::pair<std::string, std::string>>& seen, RegistryEntry e,
              const std::string& path) {
    if (!seen.emplace(e.id, e.version).second)
        fail(path, fmt::format("{} appears twice", plugin_name(e.id, e.version)));
    entries.push_back(std::move(e));
}

}  // namespace

Result<Registry> Registry::parse(std::string_view json_text, std::string_view name) {
    // Strict: a key written twice (a second binary_sha256 in an entry, say) is refused, so
    // what a reviewer reads in the file is what the host uses.
    auto parsed = parse_json_strict(json_text, name);
    if (!parsed) return parsed.error();
    const json& doc = parsed.value();
    Registry registry;
    auto read = read_json(name, [&] {
        expect_object(doc, "", {"format", "plugins"});
        if (const std::string format = text(doc, "", "format"); format != kFormat)
            fail("format", fmt::format("\"{}\" is not \"{}\"", format, kFormat));
        const json& plugins = array(doc["plugins"], "plugins");
        std::set<std::pair<std::string, std::string>> seen;
        for (size_t i = 0; i < plugins.size(); ++i) {
            const std::string path = fmt::format("plugins[{}]", i);
            add_once(registry.entries_, seen, read_entry(plugins[i], path), path);
        }
    });
    if (!read) return read.error();
    std::sort(registry.entries_.begin(), registry.entries_.end(), entry_less);
    return registry;
}

Result<Registry> Registry::parse_selected(std::string_view json_text, std::string_view name,
                                          const std::function<bool(std::string_view)>& wanted) {
    const auto scanned = scan_registry(json_text);
    // Not the shape the registry writes: the full reader refuses it with its usual message.
    if (!scanned || scanned->format != kFormat) return parse(json_text, name);
    Registry registry;
    std::set<std::pair<std::string, std::string>> seen;
    for (size_t i = 0; i < scanned->entries.size(); ++i) {
        if (!wanted(scanned->entries[i])) continue;
        const std::string path = fmt::format("plugins[{}]", i);
        auto parsed = parse_json_strict(scanned->entries[i], fmt::format("{}: {}", name, path));
        if (!parsed) return parsed.error();
        auto read = read_json(name, [&] {
            add_once(registry.entries_, seen, read_entry(parsed.value(), path), path);
        });
        if (!read) return read.error();
    }
    std::sort(registry.entries_.begin(), registry.entries_.end(), entry_less);
    return registry;
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
        if (!e.waivers.empty()) {
            j["waivers"] = ordered_json::array();
            for (const Waiver& w : e.waivers) j["waivers"].push_back(write_waiver(w));
        }
        plugins.push_back(std::move(j));
    }
    const ordered_json doc = {{"format", std::string(kFormat)}, {"plugins", plugins}};
    return doc.dump(2) + "\n";
}

}  // namespace acetate
