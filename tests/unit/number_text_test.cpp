// The one reader of values typed as text (host/core/number_text.hpp), the registry's days that
// go through it, and the check that outputs never replace inputs (host/core/output_paths.hpp).
// No GPU, no device, no environment needed.

#include "core/number_text.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "core/output_paths.hpp"
#include "core/sha256.hpp"
#include "registry.hpp"
#include "registry_fields.hpp"

namespace acetate {
namespace {

namespace fs = std::filesystem;
using namespace number_text;

template <class T>
std::string refusal(const Result<T>& r) {
    return r ? "(accepted)" : r.error().message;
}

constexpr double kHuge = std::numeric_limits<double>::max();

TEST(NumberText, FiniteNumbersWithinTheirRange) {
    EXPECT_EQ(finite_number("2.5", "--time", 0, kHuge).value(), 2.5);
    EXPECT_EQ(finite_number("-1e3", "--time", -kHuge, kHuge).value(), -1000.0);
    EXPECT_EQ(finite_number(".5", "--warn", 0, 1).value(), 0.5);
    EXPECT_EQ(finite_number("0", "--fail", 0, 1).value(), 0.0);
    // Below the smallest double: its nearest double, not an error.
    EXPECT_EQ(finite_number("1e-400", "--warn", 0, 1).value(), 0.0);
}

TEST(NumberText, NotFiniteIsRefusedAsSuch) {
    for (const char* text : {"nan", "NaN", "inf", "-inf", "Infinity", "+nan"})
        EXPECT_EQ(refusal(finite_number(text, "--time", -kHuge, kHuge)),
                  std::string("--time: must be a finite number, got \"") + text + "\"");
    EXPECT_EQ(refusal(finite_number("1e999", "--time", -kHuge, kHuge)),
              "--time: must be a finite number, got \"1e999\"");
}

TEST(NumberText, OutOfRangeNamesTheLimit) {
    EXPECT_EQ(refusal(finite_number("-1", "--fail", 0, kHuge)),
              "--fail: must be at least 0, got -1");
    EXPECT_EQ(refusal(finite_number("1e39", "--time", -3.4e38, 3.4e38)),
              "--time: must be at most 3.4e+38, got 1e39");
    EXPECT_EQ(refusal(finite_number("3601", "--timeout", 1, 3600)),
              "--timeout: must be at most 3600, got 3601");
}

TEST(NumberText, OnlyTheNumberItself) {
    for (const char* text :
         {"", "3x", " 3", "3 ", "+3", "0x10", "1e", "1e+", ".", "-", "1..2", "1,5", "--3"})
        EXPECT_EQ(refusal(finite_number(text, "--warn", -kHuge, kHuge)),
                  "--warn: must be a number, got " + nlohmann::json(text).dump())
            << text;
}

TEST(NumberText, IntegersFitOrAreRefused) {
    EXPECT_EQ(integer("-7", "--n", -10, 10).value(), -7);
    EXPECT_EQ(integer("-9223372036854775808", "--n", INT64_MIN, INT64_MAX).value(), INT64_MIN);
    EXPECT_EQ(integer("9223372036854775807", "--n", INT64_MIN, INT64_MAX).value(), INT64_MAX);
    EXPECT_EQ(refusal(integer("9223372036854775808", "--n", INT64_MIN, INT64_MAX)),
              "--n: must be at most 9223372036854775807, got 9223372036854775808");
    EXPECT_EQ(refusal(integer("-9223372036854775809", "--n", INT64_MIN, INT64_MAX)),
              "--n: must be at least -9223372036854775808, got -9223372036854775809");
    EXPECT_EQ(refusal(integer("11", "--strictness", 1, 10)),
              "--strictness: must be at most 10, got 11");
    EXPECT_EQ(refusal(integer("0", "--strictness", 1, 10)),
              "--strictness: must be at least 1, got 0");
    for (const char* text : {"1.5", "1e3", "3x", "", "+1", " 1", "nan", "0x1"})
        EXPECT_EQ(refusal(integer(text, "--strictness", 1, 10)),
                  "--strictness: must be an integer, got " + nlohmann::json(text).dump())
            << text;
}

TEST(NumberText, UnsignedNeverWraps) {
    EXPECT_EQ(unsigned_integer("18446744073709551615", "--seed", 0, UINT64_MAX).value(),
              UINT64_MAX);
    EXPECT_EQ(unsigned_integer("-0", "--seed", 0, UINT64_MAX).value(), 0u);
    EXPECT_EQ(refusal(unsigned_integer("-1", "--seed", 0, UINT64_MAX)),
              "--seed: must be at least 0, got -1");
    EXPECT_EQ(refusal(unsigned_integer("18446744073709551616", "--shuffle-seed", 0, UINT64_MAX)),
              "--shuffle-seed: must be at most 18446744073709551615, got 18446744073709551616");
    EXPECT_EQ(refusal(unsigned_integer("-99999999999999999999", "--seed", 0, UINT64_MAX)),
              "--seed: must be at least 0, got -99999999999999999999");
    EXPECT_EQ(refusal(read<uint32_t>("4294967296", "--floor")),
              "--floor: must be at most 4294967295, got 4294967296");
    EXPECT_EQ(refusal(read<unsigned>("0", "--jobs", 1u, 256u)),
              "--jobs: must be at least 1, got 0");
}

TEST(NumberText, ALongArgumentIsShownShortened) {
    const std::string text(100000, '7');
    const std::string message = refusal(unsigned_integer(text, "--seed", 0, UINT64_MAX));
    EXPECT_EQ(message, "--seed: must be at most 18446744073709551615, got " + std::string(64, '7') +
                           "... (100000 characters)");
}

TEST(NumberText, DaysThatExist) {
    EXPECT_TRUE(day("2024-02-29", "--until"));  // divisible by 4
    EXPECT_TRUE(day("2000-02-29", "--until"));  // divisible by 400
    EXPECT_TRUE(day("2026-12-31", "--until"));
    EXPECT_EQ(refusal(day("2026-02-30", "--until")),
              "--until: must be a day that exists, got 2026-02-30 (February 2026 has 28 days)");
    EXPECT_EQ(refusal(day("2100-02-29", "--until")),
              "--until: must be a day that exists, got 2100-02-29 (February 2100 has 28 days)");
    EXPECT_EQ(refusal(day("2026-04-31", "--until")),
              "--until: must be a day that exists, got 2026-04-31 (April 2026 has 30 days)");
    EXPECT_EQ(refusal(day("2026-13-01", "--until")),
              "--until: must be a day that exists, got 2026-13-01 (there is no month 13)");
    EXPECT_EQ(refusal(day("2026-01-00", "--until")),
              "--until: must be a day that exists, got 2026-01-00 (January 2026 has 31 days)");
    for (const char* text : {"2026-2-3", "2026-02-03T00:00:00Z", "", "26-02-03", "2026/02/03",
                             " 2026-02-03", "2026-02-0x"})
        EXPECT_EQ(refusal(day(text, "--until")),
                  "--until: must be a day YYYY-MM-DD, got " + nlohmann::json(text).dump())
            << text;
}

TEST(NumberText, NamesAreNotBlank) {
    EXPECT_EQ(name("Ada Lovelace", "--by").value(), "Ada Lovelace");
    EXPECT_EQ(refusal(name("", "--by")), "--by: must not be empty");
    EXPECT_EQ(refusal(name("   ", "--reviewer")),
              "--reviewer: must not be only spaces, got \"   \"");
    EXPECT_EQ(refusal(name("a\nb", "--by")),
              "--by: must be one line without control characters, got \"a\\nb\"");
}

// The registry's days and times go through the same reader: a waiver until a day that does
// not exist is refused when granted and when read from a file.
TEST(RegistryDays, ADayThatDoesNotExistIsRefused) {
    EXPECT_TRUE(registry_fields::is_day("2028-02-29"));
    EXPECT_FALSE(registry_fields::is_day("2026-02-30"));
    EXPECT_FALSE(registry_fields::is_day("2100-02-29"));
    EXPECT_TRUE(registry_fields::is_timestamp("2024-02-29T23:59:59Z"));
    EXPECT_FALSE(registry_fields::is_timestamp("2026-02-30T12:00:00Z"));
    EXPECT_FALSE(registry_fields::is_timestamp("2026-04-31T12:00:00Z"));

    const std::string id = "org.acetate.glow", version = "2.0.0";
    const std::string binary = sha256_hex("binary"), source = sha256_hex("source");
    Registry r;
    r.set_clock([] { return std::string("2026-11-26T12:00:00Z"); });
    ASSERT_TRUE(r.record_review(id, version, binary, source, "alice@example.org", "read"));
    auto waive = [&](const std::string& until) {
        return r.waive(id, version, binary, source,
                       Waiver{"coverage", "by design", "bob@example.org", "", until, ""});
    };
    EXPECT_EQ(refusal(waive("2027-02-29")),
              "org.acetate.glow 2.0.0: waiver refused: --until \"2027-02-29\" is not a day "
              "(YYYY-MM-DD)");
    ASSERT_TRUE(waive("2028-02-29"));
    std::string text = r.to_json();
    const size_t at = text.find("\"2028-02-29\"");
    ASSERT_NE(at, std::string::npos) << text;
    text.replace(at, 12, "\"2026-02-30\"");
    auto parsed = Registry::parse(text, "registry.json");
    ASSERT_FALSE(parsed);
    EXPECT_NE(parsed.error().message.find("until: \"2026-02-30\" is not a day (YYYY-MM-DD)"),
              std::string::npos)
        << parsed.error().message;
}

// Outputs never replace inputs, whatever the name: the same path, "./" and "..", a symbolic
// link and a hard link to an input are all that input.
TEST(OutputPaths, AnOutputThatIsAnInputByAnyNameIsRefused) {
    const fs::path dir =
        fs::temp_directory_path() / ("acetate-output-paths-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir / "sub");
    std::ofstream(dir / "plugin.so") << "bytes";
    fs::create_symlink(dir / "plugin.so", dir / "link.so");
    fs::create_hard_link(dir / "plugin.so", dir / "hard.so");
    const std::vector<RunFile> inputs{{dir / "scene.json", "scene"},
                                      {dir / "plugin.so", "the plugin"}};
    for (const fs::path& out :
         {dir / "plugin.so", dir / "sub" / ".." / "plugin.so", dir / "link.so", dir / "hard.so"}) {
        auto checked = check_outputs_spare_inputs({{out, "--json"}}, inputs);
        ASSERT_FALSE(checked) << out;
        EXPECT_EQ(checked.error().message,
                  "--json " + out.string() +
                      ": would overwrite an input of this run (the plugin: " +
                      (dir / "plugin.so").string() + ")");
    }
    EXPECT_TRUE(check_outputs_spare_inputs({{dir / "report.json", "--json"}}, inputs));
    auto twice = check_outputs_spare_inputs(
        {{dir / "out.xml", "--json"}, {dir / "sub" / ".." / "out.xml", "--junit"}}, inputs);
    ASSERT_FALSE(twice);
    EXPECT_EQ(twice.error().message, "--junit " + (dir / "sub" / ".." / "out.xml").string() +
                                         ": is also the output of --json (" +
                                         (dir / "out.xml").string() + ")");
    fs::remove_all(dir);
}

}  // namespace
}  // namespace acetate
