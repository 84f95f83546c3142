#pragma once
// Text and grouping shared by acetate-bench's HTML page (report_html.cpp) and its charts
// (report_svg.cpp). Scene names, plugin ids and commands come from files, so every piece of
// text goes through escape() and every image name through url().

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "bench_results.hpp"

namespace acetate::bench::report_detail {

// Text safe in element content and quoted attributes, in HTML and in SVG (XML). Control
// characters are dropped: neither can show them and in XML they are errors.
std::string escape(std::string_view text);

// A relative file name as a URL: everything outside the unreserved set is percent-encoded, so a
// name can neither become a scheme ("javascript:") nor leave the attribute.
std::string url(std::string_view path);

// Numbers as the page and the charts print them: milliseconds, errors, PSNR (∞ when
// infinite), shares as percentages, and a configuration as "preset · format".
std::string ms_text(double ms);
std::string error_text(double value);
std::string psnr_text(double db);
std::string share_text(double share);

// 2073600 as "2 073 600" (narrow no-break spaces): pixel counts are read by their size.
std::string count_text(uint64_t n);
std::string label(const ConfigResult& c);

// One (scene, plugin) pair's configurations in the runner's order, and which of them are on
// the Pareto front of (median ms, mean |error|). "off" is not a way to run the effect and a
// configuration with a non-finite image is not a choice anyone should make, so neither is
// offered (NaN keeps a point off the front and stops it dominating).
struct Group {
    std::string scene, plugin;
    std::vector<const ConfigResult*> configs;
    std::vector<bool> front;
};

std::vector<Group> groups_of(const BenchResults& results);

// The speed-against-error chart of one group, as a standalone SVG document (report.hpp).
std::string chart_svg(const Group& group);

}  // namespace acetate::bench::report_detail
