#include "case_runner.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>

#include "case_kinds.hpp"
#include "core/atomic_file.hpp"
#include "process_hygiene.hpp"

namespace acetate::harness {

namespace fs = std::filesystem;

fs::path case_result_file(const fs::path& case_directory) {
    return case_directory / "result.json";
}

fs::path case_log_file(const fs::path& case_directory) {
    return case_directory / "log.txt";
}

namespace {

// From here on this process's stdout and stderr go to `log` (appended to: the parent opened
// the first case's log for the process and may have written to it).
Result<void> send_output_to(const fs::path& log) {
    std::fflush(stdout);
    std::fflush(stderr);
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (fd < 0)
        return make_error(ErrorCode::Io, fmt::format("{}: cannot open the case's log: {}",
                                                     log.string(), std::strerror(errno)));
    const bool moved = ::dup2(fd, STDOUT_FILENO) >= 0 && ::dup2(fd, STDERR_FILENO) >= 0;
    const int saved = errno;
    ::close(fd);
    if (!moved)
        return make_error(ErrorCode::Io, fmt::format("{}: cannot send output to it: {}",
                                                     log.string(), std::strerror(saved)));
    return {};
}

// One case on `device` (none: it opens one); the device is handed back in `device` unless this
// is the last case, which closes it before its checks are taken.
Result<CaseResult> run_one(const CaseContext& c, std::unique_ptr<VulkanContext>& device,
                           bool last) {
    std::error_code ec;
    fs::create_directories(c.case_directory, ec);
    if (ec)
        return make_error(ErrorCode::Io, fmt::format("{}: cannot create: {}",
                                                     c.case_directory.string(), ec.message()));
    ACETATE_TRY(send_output_to(case_log_file(c.case_directory)));
    const auto start = std::chrono::steady_clock::now();
    const uint64_t messages_before = VulkanContext::process_validation_message_count();
    // Every plugin call of the case (loads, builds, unloads) is compared before and after.
    ProcessHygieneWatcher hygiene;
    auto session = open_session(c, std::move(device));
    if (!session) return session.error();
    CaseWriter writer(c);
    const Result<void> ran = case_kind_info(c.spec.kind).run(c, *session, writer);
    if (!ran) return ran.error();
    // The renderer goes first (the plugin is unloaded with it); the last case closes Vulkan
    // before its checks: messages at teardown (objects left alive) count too.
    const bool validation_layer_on = session->context->validation_enabled();
    session->renderer.reset();
    if (last)
        session->context.reset();
    else
        device = std::move(session->context);
    writer.add(hygiene.check());
    CaseResult result = writer.finish(validation_layer_on, messages_before);
    result.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace

Result<void> run_cases(const std::vector<CaseContext>& cases) {
    std::unique_ptr<VulkanContext> device;
    for (size_t i = 0; i < cases.size(); ++i) {
        const CaseContext& c = cases[i];
        auto result = run_one(c, device, i + 1 == cases.size());
        if (!result) return result.error();
        ACETATE_TRY(write_file_atomically(case_result_file(c.case_directory),
                                          to_json(result.value()).dump(2)));
    }
    return {};
}

}  // namespace acetate::harness
