#pragma once
// GPU time of one recorded step of a frame (CompositorOptions::gpu_timings): what GpuTimer
// measures and FrameStats hands on. Its own header so the timer needs nothing from render/.

#include <string>

namespace acetate {

struct PassTiming {
    std::string name;  // "floor 0 tiles", a pass's label ("floor0.acetate.water.shade"), "output"
    double milliseconds = 0;
};

}  // namespace acetate
