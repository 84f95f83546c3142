#pragma once
// `acetate render --stats FILE`: what a load and each frame did, as JSON (docs/OVERVIEW.md,
// "What a frame reports"), from the embedding API's statistics. The field names are binding:
// tests and scripts read them.

#include <nlohmann/json.hpp>

#include "acetate/host/host.hpp"

namespace acetate {

nlohmann::json to_json(const host::FrameStatistics& frame);
nlohmann::json to_json(const host::LoadStatistics& load);
nlohmann::json to_json(const host::ImageInfo& image);

}  // namespace acetate
