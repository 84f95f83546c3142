// The persisted VkPipelineCache file: a round trip returns the driver's bytes; a missing file is
// a first run; every stale, damaged or foreign file gives one line naming the file and the check
// that failed (and never reaches the driver); writes are atomic. No GPU needed: the driver data
// is built by hand with a valid VkPipelineCacheHeaderVersionOne.

#include "vulkan/pipeline_cache_file.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <future>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "test_files.hpp"

namespace acetate {
namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<uint8_t>;

PipelineCacheIdentity test_identity() {
    PipelineCacheIdentity id;
    id.vendor_id = 0x10de;
    id.device_id = 0x2330;
    id.driver_version = 0x8a0c4000;
    for (size_t i = 0; i < id.pipeline_cache_uuid.size(); ++i)
        id.pipeline_cache_uuid[i] = uint8_t(0xa0 + i);
    return id;
}

// What vkGetPipelineCacheData would return for `id`: the spec's header (little-endian) and an
// opaque payload.
Bytes driver_data(const PipelineCacheIdentity& id, size_t payload = 200) {
    Bytes out;
    auto u32 = [&](uint32_t v) {
        for (int i = 0; i < 4; ++i) out.push_back(uint8_t(v >> (8 * i)));
    };
    u32(sizeof(VkPipelineCacheHeaderVersionOne));
    u32(VK_PIPELINE_CACHE_HEADER_VERSION_ONE);
    u32(id.vendor_id);
    u32(id.device_id);
    out.insert(out.end(), id.pipeline_cache_uuid.begin(), id.pipeline_cache_uuid.end());
    for (size_t i = 0; i < payload; ++i) out.push_back(uint8_t(i * 7 + 3));
    return out;
}

Bytes read_bytes(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return Bytes(std::istreambuf_iterator<char>(in), {});
}

void write_bytes(const fs::path& file, const Bytes& bytes) {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    ASSERT_TRUE(out.good()) << file;
}

class PipelineCacheFileTest : public ::testing::Test {
  protected:
    void SetUp() override { dir_ = test::scratch_dir(); }

    fs::path file() const { return dir_ / "acetate" / "pipeline-cache.bin"; }

    void save(const PipelineCacheIdentity& id, const Bytes& data) {
        auto written = write_pipeline_cache(file(), id, data);
        ASSERT_TRUE(written.ok()) << written.error().message;
    }

    // Reads file() with `id`, expects a rejection, returns the message; every rejection is one
    // line that starts with the file's name.
    std::string rejection(const PipelineCacheIdentity& id = test_identity()) {
        auto read = read_pipeline_cache(file(), id);
        if (read.ok()) {
            ADD_FAILURE() << "file accepted, expected a rejection";
            return "";
        }
        const std::string& message = read.error().message;
        EXPECT_EQ(read.error().code, ErrorCode::InvalidInput) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        EXPECT_EQ(message.rfind(file().string() + ": ", 0), 0u) << message;
        return message;
    }

    // Names in the cache folder other than the cache file itself: leftover temporaries.
    std::vector<std::string> strays() const {
        std::vector<std::string> names;
        for (const auto& entry : fs::directory_iterator(file().parent_path()))
            if (entry.path() != file()) names.push_back(entry.path().filename().string());
        return names;
    }

    fs::path dir_;
};

TEST_F(PipelineCacheFileTest, RoundTripReturnsTheDriverData) {
    const Bytes data = driver_data(test_identity());
    save(test_identity(), data);
    auto read = read_pipeline_cache(file(), test_identity());
    ASSERT_TRUE(read.ok()) << read.error().message;
    EXPECT_EQ(*read, data);
    // Our header (84 bytes) and the data, nothing else.
    EXPECT_EQ(fs::file_size(file()), 84 + data.size());
    EXPECT_TRUE(strays().empty());
}

// lavapipe's whole cache is the 32-byte header (docs/design.md, "Facts about lavapipe"): that
// must round-trip too.
TEST_F(PipelineCacheFileTest, HeaderOnlyDriverDataRoundTrips) {
    const Bytes data = driver_data(test_identity(), 0);
    save(test_identity(), data);
    auto read = read_pipeline_cache(file(), test_identity());
    ASSERT_TRUE(read.ok()) << read.error().message;
    EXPECT_EQ(*read, data);
}

TEST_F(PipelineCacheFileTest, SecondWriteReplacesTheFirst) {
    save(test_identity(), driver_data(test_identity(), 500));
    const Bytes smaller = driver_data(test_identity(), 10);
    save(test_identity(), smaller);
    auto read = read_pipeline_cache(file(), test_identity());
    ASSERT_TRUE(read.ok()) << read.error().message;
    EXPECT_EQ(*read, smaller);
    EXPECT_TRUE(strays().empty());
}

TEST_F(PipelineCacheFileTest, MissingFileIsAnEmptyCache) {
    auto read = read_pipeline_cache(file(), test_identity());
    ASSERT_TRUE(read.ok()) << read.error().message;
    EXPECT_TRUE(read->empty());
}

TEST_F(PipelineCacheFileTest, StaleIdentityNamesTheCheck) {
    save(test_identity(), driver_data(test_identity()));

    PipelineCacheIdentity other_vendor = test_identity();
    other_vendor.vendor_id = 0x1002;
    EXPECT_NE(rejection(other_vendor).find("stale: vendor id 0x10de"), std::string::npos);

    PipelineCacheIdentity other_device = test_identity();
    other_device.device_id = 0x2331;
    const std::string device = rejection(other_device);
    EXPECT_NE(device.find("stale: device id 0x2330, this device has 0x2331"), std::string::npos)
        << device;

    PipelineCacheIdentity other_driver = test_identity();
    other_driver.driver_version += 1;
    EXPECT_NE(rejection(other_driver).find("stale: driver version"), std::string::npos);

    PipelineCacheIdentity other_uuid = test_identity();
    other_uuid.pipeline_cache_uuid[15] ^= 0xff;
    EXPECT_NE(rejection(other_uuid).find("stale: pipeline cache UUID"), std::string::npos);
}

TEST_F(PipelineCacheFileTest, TruncatedFileIsRejectedAtEveryLength) {
    save(test_identity(), driver_data(test_identity()));
    const Bytes whole = read_bytes(file());
    // Inside the magic, inside the header, at its end, inside the driver header, one byte short.
    for (size_t length : {size_t(0), size_t(5), size_t(12), size_t(50), size_t(83), size_t(84),
                          size_t(100), size_t(84 + 32), whole.size() - 1}) {
        SCOPED_TRACE(length);
        write_bytes(file(), Bytes(whole.begin(), whole.begin() + length));
        const std::string message = rejection();
        const bool named = message.find("truncated") != std::string::npos ||
                           message.find("data size mismatch") != std::string::npos;
        EXPECT_TRUE(named) << message;
    }
}

TEST_F(PipelineCacheFileTest, TrailingBytesAreASizeMismatch) {
    save(test_identity(), driver_data(test_identity()));
    Bytes longer = read_bytes(file());
    longer.push_back(0);
    write_bytes(file(), longer);
    EXPECT_NE(rejection().find("data size mismatch"), std::string::npos);
}

TEST_F(PipelineCacheFileTest, FlippedPayloadByteIsAHashMismatch) {
    save(test_identity(), driver_data(test_identity()));
    Bytes bytes = read_bytes(file());
    bytes[bytes.size() - 7] ^= 0x01;
    write_bytes(file(), bytes);
    EXPECT_NE(rejection().find("hash mismatch"), std::string::npos);
}

TEST_F(PipelineCacheFileTest, BadMagicIsRejected) {
    save(test_identity(), driver_data(test_identity()));
    Bytes bytes = read_bytes(file());
    bytes[0] = 'X';
    write_bytes(file(), bytes);
    EXPECT_NE(rejection().find("bad magic"), std::string::npos);
}

TEST_F(PipelineCacheFileTest, OtherFormatVersionIsRejected) {
    save(test_identity(), driver_data(test_identity()));
    Bytes bytes = read_bytes(file());
    bytes[12] = 2;  // format version, little-endian
    write_bytes(file(), bytes);
    EXPECT_NE(rejection().find("format version 2, expected 1"), std::string::npos);
}

TEST_F(PipelineCacheFileTest, GarbageFileIsRejected) {
    fs::create_directories(file().parent_path());
    Bytes garbage(4096);
    for (size_t i = 0; i < garbage.size(); ++i) garbage[i] = uint8_t((i * 2654435761u) >> 13);
    write_bytes(file(), garbage);
    EXPECT_NE(rejection().find("bad magic"), std::string::npos);
    test::write_text(file(), "{ \"not\": \"a pipeline cache\" }\n");
    EXPECT_NE(rejection().find("bad magic"), std::string::npos);
}

// A file whose wrapper is intact but whose driver data belongs elsewhere must not reach the
// driver. Such a file is crafted with encode (write refuses to produce one).
TEST_F(PipelineCacheFileTest, DriverHeaderMismatchIsRejected) {
    fs::create_directories(file().parent_path());
    const PipelineCacheIdentity id = test_identity();
    auto craft = [&](Bytes data) {
        auto encoded = encode_pipeline_cache(id, data);
        ASSERT_TRUE(encoded.ok());
        write_bytes(file(), *encoded);
    };

    PipelineCacheIdentity other = id;
    other.device_id = 0x1234;
    craft(driver_data(other));
    EXPECT_NE(rejection().find("driver header: device id 0x1234"), std::string::npos);

    other = id;
    other.pipeline_cache_uuid[0] = 0;
    craft(driver_data(other));
    EXPECT_NE(rejection().find("driver header: pipeline cache UUID"), std::string::npos);

    Bytes bad_version = driver_data(id);
    bad_version[4] = 2;
    craft(bad_version);
    EXPECT_NE(rejection().find("driver header: headerVersion 2"), std::string::npos);

    Bytes small_header = driver_data(id);
    small_header[0] = 16;
    craft(small_header);
    EXPECT_NE(rejection().find("driver header: headerSize 16"), std::string::npos);

    Bytes huge_header = driver_data(id, 4);
    huge_header[0] = 200;  // more than the 36 bytes there are
    craft(huge_header);
    EXPECT_NE(rejection().find("driver header: headerSize 200"), std::string::npos);

    craft(Bytes(10, 0));
    EXPECT_NE(rejection().find("driver header: 10 bytes"), std::string::npos);

    // And write refuses to save such data in the first place, leaving nothing behind.
    fs::remove(file());
    auto refused = write_pipeline_cache(file(), id, driver_data(other));
    ASSERT_FALSE(refused.ok());
    EXPECT_EQ(refused.error().code, ErrorCode::InvalidInput);
    EXPECT_FALSE(fs::exists(file()));
}

TEST_F(PipelineCacheFileTest, WriteUnderARegularFileFails) {
    test::write_text(dir_ / "blocker", "a file where a folder should be");
    const fs::path blocked = dir_ / "blocker" / "acetate" / "pipeline-cache.bin";
    auto written = write_pipeline_cache(blocked, test_identity(), driver_data(test_identity()));
    ASSERT_FALSE(written.ok());
    EXPECT_EQ(written.error().code, ErrorCode::Io);
    EXPECT_NE(written.error().message.find(blocked.string()), std::string::npos);
    EXPECT_TRUE(fs::is_regular_file(dir_ / "blocker"));
}

// Makes write(2) fail past `bytes` (EFBIG) while alive, for every file of the process. Works as
// root, unlike a read-only directory.
class FileSizeLimit {
  public:
    explicit FileSizeLimit(rlim_t bytes) {
        old_handler_ = ::signal(SIGXFSZ, SIG_IGN);  // else the process is killed
        ::getrlimit(RLIMIT_FSIZE, &old_);
        rlimit limit = old_;
        limit.rlim_cur = bytes;
        ::setrlimit(RLIMIT_FSIZE, &limit);
    }
    ~FileSizeLimit() {
        ::setrlimit(RLIMIT_FSIZE, &old_);
        ::signal(SIGXFSZ, old_handler_);
    }

  private:
    rlimit old_{};
    sighandler_t old_handler_{};
};

TEST_F(PipelineCacheFileTest, FailedWriteLeavesTheOldFileAndNoTemporaries) {
    const Bytes old_data = driver_data(test_identity(), 100);
    save(test_identity(), old_data);
    const Bytes old_file = read_bytes(file());
    const Bytes new_data = driver_data(test_identity(), 10000);
    // Nothing is printed while the limit holds: it applies to a redirected stdout as well.
    std::optional<Result<void>> written;
    {
        FileSizeLimit limit(old_file.size() + 100);
        written.emplace(write_pipeline_cache(file(), test_identity(), new_data));
    }
    ASSERT_FALSE(written->ok());
    EXPECT_EQ(written->error().code, ErrorCode::Io);
    EXPECT_NE(written->error().message.find(file().string()), std::string::npos)
        << written->error().message;
    EXPECT_EQ(read_bytes(file()), old_file);
    EXPECT_TRUE(strays().empty());
    auto read = read_pipeline_cache(file(), test_identity());
    ASSERT_TRUE(read.ok()) << read.error().message;
    EXPECT_EQ(*read, old_data);
}

TEST_F(PipelineCacheFileTest, DirectoryInPlaceOfTheFileIsRefused) {
    fs::create_directories(file());
    auto read = read_pipeline_cache(file(), test_identity());
    ASSERT_FALSE(read.ok());
    EXPECT_EQ(read.error().code, ErrorCode::InvalidInput);
    EXPECT_NE(read.error().message.find("not a regular file (a directory)"), std::string::npos)
        << read.error().message;
}

// A FIFO where the cache should be is refused at once; opening it to read would wait forever
// for a writer.
TEST_F(PipelineCacheFileTest, FifoInPlaceOfTheFileIsRefusedAtOnce) {
    fs::create_directories(file().parent_path());
    ASSERT_EQ(::mkfifo(file().c_str(), 0644), 0);
    auto pending = std::async(std::launch::async,
                              [&] { return read_pipeline_cache(file(), test_identity()); });
    if (pending.wait_for(std::chrono::seconds(10)) != std::future_status::ready) {
        // Release the blocked reader so the test can end, then fail.
        const int writer = ::open(file().c_str(), O_WRONLY | O_NONBLOCK);
        if (writer >= 0) ::close(writer);
        FAIL() << "read_pipeline_cache blocked on a FIFO";
    }
    auto read = pending.get();
    ASSERT_FALSE(read.ok());
    EXPECT_NE(read.error().message.find("not a regular file (a FIFO)"), std::string::npos)
        << read.error().message;
}

TEST(PipelineCacheIdentityTest, IdentityOfCopiesTheProperties) {
    VkPhysicalDeviceProperties props{};
    props.vendorID = 0x10005;
    props.deviceID = 7;
    props.driverVersion = VK_MAKE_API_VERSION(0, 22, 3, 6);
    for (uint32_t i = 0; i < VK_UUID_SIZE; ++i) props.pipelineCacheUUID[i] = uint8_t(i + 1);
    const PipelineCacheIdentity id = identity_of(props);
    EXPECT_EQ(id.vendor_id, 0x10005u);
    EXPECT_EQ(id.device_id, 7u);
    EXPECT_EQ(id.driver_version, props.driverVersion);
    EXPECT_EQ(id.pipeline_cache_uuid[0], 1);
    EXPECT_EQ(id.pipeline_cache_uuid[15], 16);
}

// Sets or unsets one environment variable while alive.
class ScopedEnv {
  public:
    ScopedEnv(const char* name, const char* value) : name_(name) {
        if (const char* old = std::getenv(name)) old_ = old;
        value ? ::setenv(name, value, 1) : ::unsetenv(name);
    }
    ~ScopedEnv() { old_ ? ::setenv(name_, old_->c_str(), 1) : ::unsetenv(name_); }

  private:
    const char* name_;
    std::optional<std::string> old_;
};

TEST(PipelineCachePathTest, FollowsXdgThenHome) {
    {
        ScopedEnv xdg("XDG_CACHE_HOME", "/x/cache");
        ScopedEnv home("HOME", "/home/u");
        EXPECT_EQ(default_pipeline_cache_path(), fs::path("/x/cache/acetate/pipeline-cache.bin"));
    }
    {
        ScopedEnv xdg("XDG_CACHE_HOME", nullptr);
        ScopedEnv home("HOME", "/home/u");
        EXPECT_EQ(default_pipeline_cache_path(),
                  fs::path("/home/u/.cache/acetate/pipeline-cache.bin"));
    }
    {
        ScopedEnv xdg("XDG_CACHE_HOME", "relative/cache");  // ignored, per the XDG spec
        ScopedEnv home("HOME", "/home/u");
        EXPECT_EQ(default_pipeline_cache_path(),
                  fs::path("/home/u/.cache/acetate/pipeline-cache.bin"));
    }
    {
        ScopedEnv xdg("XDG_CACHE_HOME", nullptr);
        ScopedEnv home("HOME", nullptr);
        EXPECT_TRUE(default_pipeline_cache_path().empty());
    }
}

}  // namespace
}  // namespace acetate
