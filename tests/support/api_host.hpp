#pragma once
// The embedding API's Host as the gpu tests that drive it use it: the build tree's shipped
// plugins (allowed unvalidated: the load policy is tested in e2e/cli_policy_test.cpp), no disk
// pipeline cache, warnings dropped; and the shipped effects' reference scenes.

#include <filesystem>
#include <memory>
#include <string>

#include "acetate/host/host.hpp"

namespace acetate::test {

host::Result<std::unique_ptr<host::Host>> build_tree_host();

// validation/references/<plugin>/scenes/quay.json in the source tree.
std::filesystem::path quay_scene(const std::string& plugin);

}  // namespace acetate::test
