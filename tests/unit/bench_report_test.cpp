// acetate-bench's reports (bench/report.hpp): the JSON has every field of every struct, writes
// infinities as strings and parses back; the HTML page is written, holds a chart with a label
// per configuration, marks the Pareto front and escapes names that come from files; the chart
// alone is a balanced SVG document. No GPU needed.

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

#include "report.hpp"
#include "test_files.hpp"

namespace acetate::bench {
namespace {

using ::acetate::test::read_file;
using ::acetate::test::scratch_dir;

namespace fs = std::filesystem;
using nlohmann::json;

constexpr double kInf = std::numeric_limits<double>::infinity();

size_t count(const std::string& text, const std::string& needle) {
    size_t n = 0;
    for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1))
        ++n;
    return n;
}

ConfigResult config(const std::string& plugin, const std::string& preset, const std::string& format,
                    double median_ms, double mean_abs) {
    ConfigResult c;
    c.scene = "harbour.json";
    c.plugin = plugin;
    c.preset = preset;
    c.format = format;
    c.floor = 1;
    c.frames = 30;
    c.median_ms = median_ms;
    c.min_ms = median_ms * 0.9;
    c.max_ms = median_ms * 1.2;
    c.first_frame_ms = median_ms * 3;
    c.load_ms = 40;
    c.pixels_shaded = 1920 * 1080;
    c.error.pixels = 1920 * 1080;
    c.error.mean_abs = mean_abs;
    c.error.max_abs = mean_abs * 20;
    c.error.max_roundings = mean_abs * 20 * 1024;
    c.error.psnr_db = mean_abs == 0 ? kInf : 60;
    c.error.warn_share = mean_abs == 0 ? 0 : 0.01;
    return c;
}

// One plugin at four presets, "off", and the reference, plus a plugin whose id needs escaping.
BenchResults sample() {
    BenchResults r;
    r.device = "Test GPU (llvmpipe)";
    r.date = "2025-01-02T03:04:05Z";
    r.load = "0.50 0.40 0.30 1/100 12345";
    r.frames = 30;
    const std::string water = "acetate.water";
    r.configs.push_back(config(water, "ultra", "rgba32f", 4.0, 0));
    r.configs.back().reference = true;
    r.configs.push_back(config(water, "ultra", "rgba16f", 3.6, 2e-5));
    r.configs.push_back(config(water, "high", "rgba16f", 2.5, 1e-4));
    r.configs.push_back(config(water, "medium", "rgba16f", 2.6, 3e-4));  // dominated by high
    r.configs.push_back(config(water, "low", "rgba16f", 1.5, 2e-3));
    r.configs.push_back(config(water, "off", "rgba16f", 1.0, 5e-2));
    r.configs[2].gpu_passes = {{"floor 1 tiles", 0.5}, {"floor 1 acetate.water:shade", 1.5}};
    r.configs[2].gpu_total_ms = 2.0;
    r.configs[2].heat_map = "acetate.water high rgba16f.png";
    r.configs.push_back(config("<&>", "low", "rgba16f", 1.0, 1e-3));
    r.configs.back().error.finite = false;
    r.configs.back().error.max_abs = kInf;
    r.configs.back().error.mean_abs = std::nan("");

    PeerComparison peer;
    peer.scene = "harbour.json";
    peer.tool = "oiiotool --over";
    peer.command = "oiiotool a.exr b.exr --over -o out.exr";
    peer.tool_ms = 300;
    peer.tool_over_ms = 20;
    peer.acetate_frame_ms = 2;
    peer.acetate_run_ms = 150;
    peer.difference.psnr_db = kInf;
    peer.note = "oiiotool reads & writes files";
    r.peers.push_back(peer);
    return r;
}

std::set<std::string> keys(const json& object) {
    std::set<std::string> out;
    for (const auto& [key, value] : object.items()) out.insert(key);
    return out;
}

TEST(BenchJson, EveryFieldIsWritten) {
    const json j = to_json(sample());
    EXPECT_EQ(keys(j), (std::set<std::string>{"device", "date", "load", "frames", "thresholds",
                                              "configs", "peers", "limits"}));
    EXPECT_EQ(keys(j["thresholds"]), (std::set<std::string>{"warn", "fail"}));
    EXPECT_EQ(j["thresholds"]["warn"].get<double>(), 1.0 / 1024.0);
    ASSERT_EQ(j["configs"].size(), 7u);
    const std::set<std::string> config_keys = {
        "scene",          "plugin",  "preset",     "format",       "reference",
        "floor",          "frames",  "median_ms",  "min_ms",       "max_ms",
        "first_frame_ms", "load_ms", "gpu_passes", "gpu_total_ms", "effect_gpu_ms",
        "pixels_shaded",  "error",   "heat_map"};
    const std::set<std::string> error_keys = {"pixels",  "max_roundings", "max_abs",    "mean_abs",
                                              "psnr_db", "warn_share",    "fail_share", "finite"};
    for (const json& c : j["configs"]) {
        EXPECT_EQ(keys(c), config_keys);
        EXPECT_EQ(keys(c["error"]), error_keys);
    }
    const json& high = j["configs"][2];
    EXPECT_EQ(high["preset"], "high");
    EXPECT_EQ(high["floor"], 1);
    EXPECT_EQ(high["pixels_shaded"], 1920 * 1080);
    EXPECT_EQ(high["heat_map"], "acetate.water high rgba16f.png");
    ASSERT_EQ(high["gpu_passes"].size(), 2u);
    EXPECT_EQ(keys(high["gpu_passes"][1]), (std::set<std::string>{"name", "milliseconds"}));
    EXPECT_EQ(high["gpu_passes"][1]["milliseconds"], 1.5);
    EXPECT_EQ(high["error"]["psnr_db"], 60.0);
    ASSERT_EQ(j["peers"].size(), 1u);
    EXPECT_EQ(keys(j["peers"][0]),
              (std::set<std::string>{"scene", "tool", "command", "tool_ms", "tool_over_ms",
                                     "acetate_frame_ms", "acetate_run_ms", "difference", "note"}));
    EXPECT_EQ(keys(j["peers"][0]["difference"]), error_keys);
}

TEST(BenchJson, InfinityIsAStringAndNaNIsNull) {
    const json j = to_json(sample());
    EXPECT_EQ(j["configs"][0]["error"]["psnr_db"], "inf");
    EXPECT_EQ(j["configs"][0]["reference"], true);
    EXPECT_EQ(j["configs"][6]["error"]["max_abs"], "inf");
    EXPECT_TRUE(j["configs"][6]["error"]["mean_abs"].is_null());
    EXPECT_EQ(j["configs"][6]["error"]["finite"], false);
    EXPECT_EQ(j["peers"][0]["difference"]["psnr_db"], "inf");
}

TEST(BenchJson, WrittenFileParsesBack) {
    const fs::path file = scratch_dir() / "sub" / "bench.json";
    const BenchResults results = sample();
    const Result<void> written = write_json(file, results);
    ASSERT_TRUE(written.ok()) << written.error().message;
    const json back = json::parse(read_file(file));  // throws on malformed JSON
    EXPECT_EQ(back, to_json(results));
    EXPECT_EQ(back["configs"][6]["plugin"], "<&>");
}

TEST(BenchHtml, PageHoldsChartTablesAndLabels) {
    const fs::path dir = scratch_dir() / "report";
    const Result<void> written = write_html(dir, sample());
    ASSERT_TRUE(written.ok()) << written.error().message;
    const std::string html = read_file(dir / "index.html");
    EXPECT_EQ(html.rfind("<!doctype html>", 0), 0u);
    EXPECT_NE(html.find("</html>"), std::string::npos);
    EXPECT_EQ(count(html, "<svg"), count(html, "</svg>"));
    EXPECT_NE(html.find("<svg"), std::string::npos);
    EXPECT_NE(html.find("Test GPU (llvmpipe)"), std::string::npos);
    EXPECT_NE(html.find("acetate.water on harbour.json <span class=\"muted\">(floor 1)</span>"),
              std::string::npos);
    EXPECT_NE(html.find("2\u202f073\u202f600"), std::string::npos);  // pixels shaded
    // A point label per configuration, "off" as the dashed line instead.
    for (const char* label : {"ultra · rgba32f", "ultra · rgba16f", "high · rgba16f",
                              "medium · rgba16f", "low · rgba16f"})
        EXPECT_NE(html.find(fmt::format(">{}</text>", label)), std::string::npos) << label;
    EXPECT_EQ(html.find(">off · rgba16f</text>"), std::string::npos);
    EXPECT_NE(html.find("without the effect"), std::string::npos);
    EXPECT_NE(html.find("0 (reference)"), std::string::npos);
    EXPECT_NE(html.find("<polyline"), std::string::npos);
    // The front of acetate.water: ultra32 (0 error), ultra16, high, low; not medium, not off.
    // The other plugin's only config has a non-finite image: not on any front.
    EXPECT_EQ(count(html, "<tr class=\"front\">"), 4u);
    EXPECT_NE(html.find("∞"), std::string::npos);  // the reference's PSNR
    // Heat map, its legend, and the GPU passes.
    EXPECT_NE(html.find("src=\"acetate.water%20high%20rgba16f.png\""), std::string::npos);
    EXPECT_NE(html.find("linearGradient"), std::string::npos);
    EXPECT_NE(html.find("floor 1 acetate.water:shade"), std::string::npos);
    EXPECT_NE(html.find("75 %"), std::string::npos);  // its share of the GPU time
    // Peers.
    EXPECT_NE(html.find("<code>oiiotool a.exr b.exr --over -o out.exr</code>"), std::string::npos);
    EXPECT_NE(html.find("2.00× / 0.50×"), std::string::npos);  // 300 ms against 150 ms
}

TEST(BenchHtml, NamesFromFilesAreEscaped) {
    BenchResults results = sample();
    results.configs[6].scene = "a\"b'.json";
    results.peers[0].command = "<script>alert(1)</script>";
    const std::string html = render_html(results);
    EXPECT_EQ(html.find("<&>"), std::string::npos);
    EXPECT_NE(html.find("&lt;&amp;&gt;"), std::string::npos);
    EXPECT_EQ(html.find("<script>"), std::string::npos);
    EXPECT_NE(html.find("&lt;script&gt;"), std::string::npos);
    EXPECT_EQ(html.find("a\"b'.json"), std::string::npos);
    EXPECT_NE(html.find("a&quot;b&#39;.json"), std::string::npos);
    EXPECT_NE(html.find("reads &amp; writes"), std::string::npos);
}

// Every start tag is closed in order, or closes itself; text has no bare '<' or '&'.
void expect_balanced(const std::string& svg) {
    std::vector<std::string> open;
    for (size_t i = 0; i < svg.size(); ++i) {
        if (svg[i] == '&') {
            const size_t end = svg.find(';', i);
            ASSERT_NE(end, std::string::npos) << "bare & at " << i;
            ASSERT_LT(end - i, 8u) << "bare & at " << i;
            continue;
        }
        if (svg[i] != '<') continue;
        const size_t end = svg.find('>', i);
        ASSERT_NE(end, std::string::npos);
        std::string tag = svg.substr(i + 1, end - i - 1);
        if (tag.starts_with("/")) {
            ASSERT_FALSE(open.empty()) << tag;
            EXPECT_EQ(open.back(), tag.substr(1)) << "at " << i;
            open.pop_back();
        } else if (!tag.ends_with("/")) {
            open.push_back(tag.substr(0, tag.find_first_of(" \n")));
        }
        i = end;
    }
    EXPECT_TRUE(open.empty()) << open.size() << " unclosed, the last " << open.back();
}

TEST(BenchSvg, ChartAloneIsABalancedDocument) {
    const BenchResults results = sample();
    for (const auto& [scene, plugin] :
         {std::pair<std::string, std::string>("harbour.json", "acetate.water"),
          {"harbour.json", "<&>"},
          {"nowhere.json", "acetate.water"}}) {
        const std::string svg = speed_error_svg(results, scene, plugin);
        EXPECT_EQ(svg.rfind("<svg xmlns=\"http://www.w3.org/2000/svg\"", 0), 0u) << plugin;
        const std::string trimmed = svg.substr(0, svg.find_last_not_of(" \n") + 1);
        EXPECT_TRUE(trimmed.ends_with("</svg>")) << plugin;
        expect_balanced(svg);
    }
    EXPECT_NE(speed_error_svg(results, "nowhere.json", "acetate.water").find("No results"),
              std::string::npos);
    // The non-finite configuration sits on its own row.
    EXPECT_NE(speed_error_svg(results, "harbour.json", "<&>").find("not finite"),
              std::string::npos);
}

TEST(BenchHtml, AnUnwritableFolderIsAnErrorNamingIt) {
    const fs::path file = scratch_dir() / "file";
    std::ofstream(file) << "x";
    const Result<void> written = write_html(file / "report", sample());
    ASSERT_FALSE(written.ok());
    EXPECT_NE(written.error().message.find(file.string()), std::string::npos);
}

}  // namespace
}  // namespace acetate::bench
