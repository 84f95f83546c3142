#include "test_signer.hpp"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "ssh_signature.hpp"
#include "test_files.hpp"

namespace acetate::test {
namespace {

namespace fs = std::filesystem;

fs::path make_key(const fs::path& file, const std::string& comment) {
    const std::string command = "ssh-keygen -q -t ed25519 -N '' -C " + shell_quote(comment) +
                                " -f " + shell_quote(file.string()) + " </dev/null";
    if (std::system(command.c_str()) != 0) ADD_FAILURE() << "could not run: " << command;
    return file;
}

std::string public_key_text(const fs::path& pub) {
    // "ssh-ed25519 AAAA… comment": the allowed-signers line takes the first two fields.
    std::istringstream in(read_file(pub));
    std::string type, blob;
    in >> type >> blob;
    return type + " " + blob;
}

TestSigner make_signer() {
    std::string name = (fs::temp_directory_path() / "acetate-test-signer-XXXXXX").string();
    if (!mkdtemp(name.data())) ADD_FAILURE() << "cannot create " << name;
    static fs::path folder;
    folder = name;
    std::atexit([] {
        std::error_code ec;
        fs::remove_all(folder, ec);
    });
    TestSigner s;
    s.key = make_key(folder / "maintainer", "acetate test maintainer");
    s.public_key = folder / "maintainer.pub";
    s.unlisted_key = make_key(folder / "stranger", "a key nobody allowed");
    s.runner_key = make_key(folder / "runner", "acetate test shard runner");
    s.allowed_signers = folder / "allowed_signers";
    std::ofstream out(s.allowed_signers);
    out << read_file(fs::path(ACETATE_SOURCE_VALIDATION_DIR) / "allowed_signers")
        << kTestSignerNames << " namespaces=\"" << kSignatureNamespace << "\" "
        << public_key_text(s.public_key) << "\n"
        << kTestRunnerName << " namespaces=\"" << kCaseResultNamespace << "\" "
        << public_key_text(fs::path(s.runner_key.string() + ".pub")) << "\n";
    return s;
}

}  // namespace

const TestSigner& test_signer() {
    static const TestSigner signer = make_signer();
    return signer;
}

std::string signer_environment() {
    return "ACETATE_ALLOWED_SIGNERS=" + shell_quote(test_signer().allowed_signers.string()) +
           " ACETATE_SIGNING_KEY=" + shell_quote(test_signer().key.string()) +
           " ACETATE_RUNNER=" + shell_quote(kTestRunnerName) +
           " ACETATE_RUNNER_KEY=" + shell_quote(test_signer().runner_key.string());
}

void sign(SignOff& s, const std::string& id, const std::string& version, ValidationStage stage,
          const std::filesystem::path& key) {
    auto signature =
        ssh_sign(key.empty() ? test_signer().key : key, sign_off_statement(id, version, stage, s));
    ASSERT_TRUE(signature) << signature.error().message;
    s.signature = signature.value();
}

}  // namespace acetate::test
