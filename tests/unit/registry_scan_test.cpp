// Reading only the entries a host needs (registry/registry_scan.hpp, Registry::parse_selected):
// the scan finds each entry as written, whatever its strings hold; the entries selected read
// exactly as the full reader reads them; a file that is not well-formed is refused with the
// full reader's own message.

#include "registry_scan.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "registry.hpp"

namespace acetate {
namespace {

// Three plugins with evidence; the second's summary holds brackets, braces, quotes and
// escapes, which a scan that counted them outside strings would trip over.
std::string three_entries() {
    Registry r;
    StageEvidence run;
    run.harness_version = "scan-test";
    run.counts = {{"PASS", 1}};
    for (int i = 0; i < 3; ++i) {
        run.summary = i == 1 ? "tricky: ] } [ { \" \\\\ \\\" end" : "plain";
        const SignOff review{"rita@example.org", "2026-11-20T10:00:00Z", "read it",
                             std::string(64, 'f'), ""};
        EXPECT_TRUE(r.record_review("org.example.p" + std::to_string(i), "1.0.0",
                                    std::string(64, char('a' + i)), std::string(64, 'f'), review));
        EXPECT_TRUE(r.record_evidence("org.example.p" + std::to_string(i), "1.0.0",
                                      std::string(64, char('a' + i)), std::string(64, 'f'),
                                      ValidationStage::AlphaTested, run));
    }
    return r.to_json();
}

TEST(RegistryScan, FindsEveryEntryAsWritten) {
    const std::string text = three_entries();
    const auto scanned = scan_registry(text);
    ASSERT_TRUE(scanned);
    EXPECT_EQ(scanned->format, Registry::kFormat);
    ASSERT_EQ(scanned->entries.size(), 3u);
    for (const std::string_view entry : scanned->entries) {
        EXPECT_EQ(entry.front(), '{');
        EXPECT_EQ(entry.back(), '}');
    }
    EXPECT_NE(scanned->entries[1].find("tricky"), std::string_view::npos);
}

TEST(RegistryScan, SelectedEntriesReadAsTheFullReaderReadsThem) {
    const std::string text = three_entries();
    auto whole = Registry::parse(text, "registry.json");
    ASSERT_TRUE(whole) << whole.error().message;
    for (int i = 0; i < 3; ++i) {
        const std::string sha(64, char('a' + i));
        auto one = Registry::parse_selected(text, "registry.json", [&](std::string_view e) {
            return e.find(sha) != std::string_view::npos;
        });
        ASSERT_TRUE(one) << one.error().message;
        ASSERT_EQ(one->entries().size(), 1u);
        EXPECT_EQ(one->entries().front(), whole->entries()[size_t(i)]);
    }
}

TEST(RegistryScan, AFileThatIsNotWellFormedIsRefusedAsTheFullReaderRefusesIt) {
    const std::string text = three_entries();
    const auto all = [](std::string_view) { return true; };
    for (const std::string& bad : std::vector<std::string>{
             text.substr(0, text.size() / 2), std::string("{\"format\": \"acetate-registry/1\"}"),
             std::string("{\"format\": \"other/1\", \"plugins\": []}"),
             "{\"format\": \"acetate-registry/1\", \"plugins\": [], \"extra\": 1}",
             "{\"format\": \"acetate-registry/1\", \"plugins\": [], \"plugins\": []}"}) {
        SCOPED_TRACE(bad);
        auto whole = Registry::parse(bad, "registry.json");
        auto selected = Registry::parse_selected(bad, "registry.json", all);
        ASSERT_FALSE(whole);
        ASSERT_FALSE(selected);
        EXPECT_EQ(selected.error().message, whole.error().message);
    }
}

// A malformed entry is refused when selected, naming its place in the whole file.
TEST(RegistryScan, ASelectedMalformedEntryIsOneLineNamingItsPlace) {
    std::string text = three_entries();
    const std::string sha(64, 'c');
    text.replace(text.find(sha), sha.size(), "not-a-digest");
    auto selected = Registry::parse_selected(text, "registry.json", [](std::string_view e) {
        return e.find("not-a-digest") != std::string_view::npos;
    });
    ASSERT_FALSE(selected);
    EXPECT_EQ(selected.error().message.rfind("registry.json: plugins[2]", 0), 0u)
        << selected.error().message;
    // Not selected, it is not read (the full reader, as `status` uses, refuses the file).
    auto others = Registry::parse_selected(text, "registry.json", [](std::string_view e) {
        return e.find(std::string(64, 'a')) != std::string_view::npos;
    });
    ASSERT_TRUE(others) << others.error().message;
    EXPECT_EQ(others->entries().size(), 1u);
    EXPECT_FALSE(Registry::parse(text, "registry.json"));
}

}  // namespace
}  // namespace acetate
