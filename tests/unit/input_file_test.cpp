// Reading inputs (core/input_file.hpp) and parsing JSON strictly (core/strict_json.hpp): every
// refusal is one line naming the file, what it is or what failed; a size over the limit is
// refused before reading; duplicate keys are refused anywhere, naming the object's JSON path.

#include "core/input_file.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstring>
#include <filesystem>
#include <string>

#include "core/strict_json.hpp"
#include "test_files.hpp"

namespace acetate {
namespace {

namespace fs = std::filesystem;

TEST(InputFile, ReadsARegularFileWhole) {
    const fs::path file = test::write_text(test::scratch_dir() / "in.json", "{\"a\": 1}\n");
    auto bytes = read_input_file(file, 9, "a test file");
    ASSERT_TRUE(bytes) << bytes.error().message;
    EXPECT_EQ(bytes.value(), "{\"a\": 1}\n") << "exactly at the limit is read";
}

TEST(InputFile, MissingFileIsFileNotFoundOrNothing) {
    const fs::path file = test::scratch_dir() / "none.json";
    auto bytes = read_input_file(file, 100, "a test file");
    ASSERT_FALSE(bytes);
    EXPECT_EQ(bytes.error().code, ErrorCode::FileNotFound);
    EXPECT_EQ(bytes.error().message, file.string() + ": file not found");
    auto maybe = read_input_file_if_exists(file, 100, "a test file");
    ASSERT_TRUE(maybe) << maybe.error().message;
    EXPECT_FALSE(maybe.value().has_value());
}

TEST(InputFile, OverTheLimitStatesTheSizeAndTheLimit) {
    const fs::path file =
        test::write_text(test::scratch_dir() / "big.json", std::string(3584, ' '));
    auto bytes = read_input_file(file, 1024, "a test file");
    ASSERT_FALSE(bytes);
    EXPECT_EQ(bytes.error().code, ErrorCode::InvalidInput);
    EXPECT_EQ(bytes.error().message,
              file.string() + ": 3.5 KiB (3584 bytes) is over the 1 KiB limit for a test file");
}

TEST(InputFile, ByteCountsReadForPeople) {
    EXPECT_EQ(describe_byte_count(1), "1 byte");
    EXPECT_EQ(describe_byte_count(1023), "1023 bytes");
    EXPECT_EQ(describe_byte_count(16 << 20), "16 MiB");
    EXPECT_EQ(describe_byte_count((uint64_t(7) << 29) + 1), "3.5 GiB (3758096385 bytes)");
}

TEST(InputFile, OnlyRegularFilesAreRead) {
    const fs::path dir = test::scratch_dir();
    const fs::path fifo = dir / "fifo";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0) << std::strerror(errno);
    struct Case {
        fs::path file;
        const char* kind;
    };
    for (const Case& c : {Case{fifo, "a FIFO"}, Case{"/dev/null", "a character device"},
                          Case{dir, "a directory"}}) {
        auto bytes = read_input_file(c.file, 100, "a test file");
        ASSERT_FALSE(bytes) << c.file;
        EXPECT_EQ(bytes.error().code, ErrorCode::InvalidInput);
        EXPECT_EQ(bytes.error().message, c.file.string() + ": not a regular file (" + c.kind + ")");
    }
}

TEST(InputFile, NameLongerThanPathMaxSaysSo) {
    const fs::path file = test::scratch_dir() / std::string(PATH_MAX, 'n');
    auto bytes = read_input_file_if_exists(file, 100, "a test file");
    ASSERT_FALSE(bytes) << "a name the kernel cannot take is not a missing file";
    EXPECT_EQ(bytes.error().code, ErrorCode::Io);
    EXPECT_TRUE(bytes.error().message == file.string() + ": cannot open: File name too long")
        << bytes.error().message.substr(bytes.error().message.size() - 60);
}

TEST(StrictJson, DuplicateKeysAreRefusedAnywhereNamingTheObject) {
    const std::pair<const char*, const char*> cases[] = {
        {R"({"a": 1, "a": 2})", "in.json: duplicate field \"a\""},
        {R"({"a": {"b": [0, {"c": 1, "d": 2, "c": 3}]}})",
         "in.json: a.b[1]: duplicate field \"c\""},
        {R"([[], [{"x": 1}, {"y": 1, "y": 1}]])", "in.json: [1][1]: duplicate field \"y\""},
    };
    for (const auto& [text, expected] : cases) {
        auto parsed = parse_json_strict(text, "in.json");
        ASSERT_FALSE(parsed) << text;
        EXPECT_EQ(parsed.error().code, ErrorCode::InvalidInput);
        EXPECT_EQ(parsed.error().message, expected);
    }
    auto fine = parse_json_strict(R"({"a": {"k": 1}, "b": {"k": 2}})", "in.json");
    ASSERT_TRUE(fine) << fine.error().message;
    EXPECT_EQ(fine.value()["b"]["k"], 2) << "the same key in two objects is no duplicate";
}

TEST(StrictJson, SyntaxErrorsAreOneLineWithoutWhatWasLastRead) {
    // An unterminated string: nlohmann quotes all of it as what it last read.
    const std::string text = "{\"a\": \"" + std::string(100000, 'x');
    auto parsed = parse_json_strict(text, "in.json");
    ASSERT_FALSE(parsed);
    EXPECT_EQ(parsed.error().code, ErrorCode::InvalidInput);
    const std::string& message = parsed.error().message;
    EXPECT_EQ(message.rfind("in.json: malformed JSON: parse error at line 1, column ", 0), 0u)
        << message.substr(0, 200);
    EXPECT_LT(message.size(), 300u) << message.substr(0, 300);
    EXPECT_EQ(message.find("last read"), std::string::npos) << message.substr(0, 300);
    EXPECT_EQ(message.find("[json.exception"), std::string::npos) << message.substr(0, 300);

    auto invalid = parse_json_strict("{\"a\": tru}", "in.json");
    ASSERT_FALSE(invalid);
    EXPECT_EQ(invalid.error().message,
              "in.json: malformed JSON: parse error at line 1, column 10: syntax error while "
              "parsing value - invalid literal");
}

TEST(StrictJson, ReadJsonFileChecksTheFileFirst) {
    const fs::path dir = test::scratch_dir();
    auto folder = read_json_file(dir, 100, "a test file");
    ASSERT_FALSE(folder);
    EXPECT_EQ(folder.error().message, dir.string() + ": not a regular file (a directory)");
    const fs::path file = test::write_text(dir / "in.json", R"({"k": 1, "k": 1})");
    auto twice = read_json_file(file, 100, "a test file");
    ASSERT_FALSE(twice);
    EXPECT_EQ(twice.error().message, file.string() + ": duplicate field \"k\"");
}

}  // namespace
}  // namespace acetate
