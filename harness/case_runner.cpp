#include "case_runner.hpp"

#include <fmt/format.h>

#include "case_kinds.hpp"
#include "process_hygiene.hpp"

namespace acetate::harness {

namespace fs = std::filesystem;

fs::path case_result_file(const fs::path& case_directory) {
    return case_directory / "result.json";
}

Result<CaseResult> run_case(const CaseContext& c) {
    std::error_code ec;
    fs::create_directories(c.case_directory, ec);
    if (ec)
        return make_error(ErrorCode::Io, fmt::format("{}: cannot create: {}",
                                                     c.case_directory.string(), ec.message()));
    // Every plugin call of the case (loads, builds, unloads) is compared before and after.
    ProcessHygieneWatcher hygiene;
    auto session = open_session(c);
    if (!session) return session.error();
    CaseWriter writer(c);
    const Result<void> ran = case_kind_info(c.spec.kind).run(c, *session, writer);
    if (!ran) return ran.error();
    // Close Vulkan first: messages at teardown (objects left alive) count too.
    const bool validation_layer_on = session->context->validation_enabled();
    session->renderer.reset();
    session->context.reset();
    writer.add(hygiene.check());
    return writer.finish(validation_layer_on);
}

}  // namespace acetate::harness
