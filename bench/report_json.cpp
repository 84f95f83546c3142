// BenchResults as JSON (report.hpp).
#include <fmt/format.h>

#include <cmath>

#include "core/atomic_file.hpp"
#include "report.hpp"

namespace acetate::bench {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// JSON numbers cannot be infinite or NaN: nlohmann would write `null` for both, losing the
// difference between "identical" (PSNR +inf) and "not measured".
json number(double value) {
    if (std::isnan(value)) return nullptr;
    if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
    return value;
}

json to_json(const ErrorStats& e) {
    return json{{"pixels", e.pixels},
                {"max_roundings", number(e.max_roundings)},
                {"max_abs", number(e.max_abs)},
                {"mean_abs", number(e.mean_abs)},
                {"psnr_db", number(e.psnr_db)},
                {"warn_share", number(e.warn_share)},
                {"fail_share", number(e.fail_share)},
                {"finite", e.finite}};
}

json to_json(const ConfigResult& c) {
    json passes = json::array();
    for (const PassTime& pass : c.gpu_passes)
        passes.push_back({{"name", pass.name}, {"milliseconds", number(pass.milliseconds)}});
    return json{{"scene", c.scene},
                {"plugin", c.plugin},
                {"preset", c.preset},
                {"format", c.format},
                {"reference", c.reference},
                {"floor", c.floor},
                {"frames", c.frames},
                {"median_ms", number(c.median_ms)},
                {"min_ms", number(c.min_ms)},
                {"max_ms", number(c.max_ms)},
                {"first_frame_ms", number(c.first_frame_ms)},
                {"load_ms", number(c.load_ms)},
                {"gpu_passes", std::move(passes)},
                {"gpu_total_ms", number(c.gpu_total_ms)},
                {"effect_gpu_ms", number(c.effect_gpu_ms)},
                {"pixels_shaded", c.pixels_shaded},
                {"error", to_json(c.error)},
                {"heat_map", c.heat_map}};
}

json to_json(const PeerComparison& p) {
    return json{{"scene", p.scene},
                {"tool", p.tool},
                {"command", p.command},
                {"tool_ms", number(p.tool_ms)},
                {"tool_over_ms", number(p.tool_over_ms)},
                {"acetate_frame_ms", number(p.acetate_frame_ms)},
                {"acetate_run_ms", number(p.acetate_run_ms)},
                {"difference", to_json(p.difference)},
                {"note", p.note}};
}

}  // namespace

json to_json(const FrameLimits& l) {
    return json{{"scene", l.scene},
                {"floor", l.floor},
                {"steady_ms", number(l.steady_ms)},
                {"first_frame_ms", number(l.first_frame_ms)},
                {"switch_floor", l.switch_floor},
                {"switch_ms", number(l.switch_ms)},
                {"switch_steady_ms", number(l.switch_steady_ms)},
                {"pixels_shaded", l.pixels_shaded},
                {"necessary_pixels", l.necessary_pixels}};
}

json to_json(const BenchResults& results) {
    json configs = json::array(), peers = json::array(), limits = json::array();
    for (const ConfigResult& c : results.configs) configs.push_back(to_json(c));
    for (const PeerComparison& p : results.peers) peers.push_back(to_json(p));
    for (const FrameLimits& l : results.limits) limits.push_back(to_json(l));
    return json{
        {"device", results.device},
        {"date", results.date},
        {"load", results.load},
        {"frames", results.frames},
        {"thresholds",
         {{"warn", number(results.thresholds.warn)}, {"fail", number(results.thresholds.fail)}}},
        {"configs", std::move(configs)},
        {"peers", std::move(peers)},
        {"limits", std::move(limits)}};
}

Result<void> write_json(const fs::path& file, const BenchResults& results) {
    if (file.has_parent_path()) {
        std::error_code ec;
        fs::create_directories(file.parent_path(), ec);
        if (ec)
            return make_error(ErrorCode::Io, fmt::format("{}: cannot create its folder: {}",
                                                         file.string(), ec.message()));
    }
    // Names come from files and may not be UTF-8; replace such bytes rather than throw.
    const std::string text =
        to_json(results).dump(2, ' ', false, json::error_handler_t::replace) + "\n";
    return write_file_atomically(file, text);
}

}  // namespace acetate::bench
