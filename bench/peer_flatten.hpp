#pragma once
// The same flattening by the tool a user would otherwise pick on a CPU: OpenImageIO's
// `oiiotool`, each tile read, decoded from sRGB, placed at its rect and composited with
// `--over`, bottom floor last, over the canvas background. Timed in the same run as acetate's
// frame of the same scene with its effects taken out.

#include <filesystem>

#include "bench_results.hpp"
#include "core/result.hpp"
#include "scene/image_io.hpp"
#include "scene/scene.hpp"

namespace acetate::bench {

struct AcetateFlattening {
    ImageRGBA image;      // a steady frame of the scene without effects
    double frame_ms = 0;  // its median frame
    double run_ms = 0;    // load + first frame + read back + EXR written, in one process
};

// Runs oiiotool `runs` times in `work_dir` (its output goes there) and compares its image with
// acetate's. Fails when oiiotool is not on PATH or exits non-zero (the message says which).
Result<PeerComparison> flatten_with_oiiotool(const SceneDesc& scene,
                                             const AcetateFlattening& acetate,
                                             const std::filesystem::path& work_dir,
                                             const ErrorThresholds& thresholds, int runs = 3);

// The oiiotool command line for a scene (exposed for the tests and the report).
std::string oiiotool_command(const SceneDesc& scene, const std::filesystem::path& output);

}  // namespace acetate::bench
