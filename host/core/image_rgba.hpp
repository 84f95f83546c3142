#pragma once
// The host's CPU image: what image files decode to (scene/image_io.hpp), what GPU images are
// uploaded from and read back into (vulkan/gpu_image.hpp). Colour inside the host is linear
// light, premultiplied RGBA float.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace acetate {

// A CPU image: RGBA float, row-major, y down (row 0 is the top).
struct ImageRGBA {
    uint32_t width = 0, height = 0;
    std::vector<float> pixels;  // width * height * 4

    ImageRGBA() = default;
    ImageRGBA(uint32_t w, uint32_t h) : width(w), height(h), pixels(size_t(w) * h * 4, 0.0f) {}
    float* at(uint32_t x, uint32_t y) { return &pixels[(size_t(y) * width + x) * 4]; }
    const float* at(uint32_t x, uint32_t y) const { return &pixels[(size_t(y) * width + x) * 4]; }
};

}  // namespace acetate
