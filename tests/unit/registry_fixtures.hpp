#pragma once
// What the registry's unit tests share: a plugin identity with two binaries and two sources, a
// passing run as evidence, a registry on a fixed clock (and one already VALIDATED), and the
// fixture that gives a test with files its own folder.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "core/sha256.hpp"
#include "registry.hpp"
#include "test_files.hpp"

namespace acetate::registry_test {

namespace fs = std::filesystem;
using Stage = ValidationStage;

inline const std::string kId = "org.acetate.bloom";
inline const std::string kVersion = "1.2.0";
inline const std::string kBinaryA = sha256_hex("binary A");
inline const std::string kBinaryB = sha256_hex("binary B (rebuilt)");
inline const std::string kSource1 = sha256_hex("source 1");
inline const std::string kSource2 = sha256_hex("source 2 (edited)");
inline const std::string kNow = "2025-11-22T08:51:00Z";

inline StageEvidence passing_run(std::string report = "reports/bloom/index.html") {
    StageEvidence ev;
    ev.harness_version = "0.1.0";
    ev.summary = "all checks passed";
    ev.counts = {{"PASS", 41}, {"WARN", 1}, {"SKIP", 2}};
    ev.report = std::move(report);
    return ev;
}

inline Registry fixed_clock_registry() {
    Registry r;
    r.set_clock([] { return kNow; });
    return r;
}

// A registry with kId at VALIDATED for binary A, source 1.
inline Registry validated_registry() {
    Registry r = fixed_clock_registry();
    EXPECT_TRUE(r.record_review(kId, kVersion, kBinaryA, kSource1, "alice", "read it all"));
    EXPECT_TRUE(
        r.record_evidence(kId, kVersion, kBinaryA, kSource1, Stage::AlphaTested, passing_run()));
    EXPECT_TRUE(
        r.record_evidence(kId, kVersion, kBinaryA, kSource1, Stage::Integrated, passing_run()));
    EXPECT_TRUE(r.promote(kId, kVersion, "bob", "integrated evidence looks right"));
    return r;
}

inline Stage stage_of(const Registry& r, const std::string& binary, const std::string& source) {
    return r.effective_stage(kId, kVersion, binary, source);
}

// Tests with files get a fresh folder, removed afterwards unless the test failed.
class RegistryFiles : public ::testing::Test {
  protected:
    void SetUp() override { dir_ = test::scratch_dir(); }
    void TearDown() override {
        if (!HasFailure()) fs::remove_all(dir_);
    }
    fs::path dir_;
};

// Child processes report through their exit status; gtest assertions stay in the parent.
template <class Body>
inline pid_t fork_child(Body body) {
    const pid_t pid = ::fork();
    if (pid == 0) ::_exit(body());
    return pid;
}

}  // namespace acetate::registry_test
