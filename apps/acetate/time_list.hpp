#pragma once
// `acetate render --times`: the times one process renders, as a list ("0,0.5,2") or a range
// START:END:STEP, each of the three S or N/D ("0:1:1/12" is 0, 1/12, ..., 11/12, 1). Every
// number goes through the one reader (core/number_text.hpp): finite, within --time's range.

#include <string_view>
#include <vector>

#include "core/result.hpp"

namespace acetate {

// At most this many times in one run: a typo like 0:1e6:0.001 is refused, not started.
inline constexpr size_t kMaxRenderTimes = 100000;

// The times `text` names, in order. Errors are one line starting "--times: ".
Result<std::vector<double>> parse_render_times(std::string_view text, double max_seconds);

}  // namespace acetate
