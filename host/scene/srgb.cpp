#include "scene/srgb.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

namespace acetate {
namespace {

float curve_to_linear(float encoded) {
    if (encoded <= 0.04045f) return encoded / 12.92f;
    return float(std::pow((double(encoded) + 0.055) / 1.055, 2.4));
}

long curve_code(float linear) {
    return std::lround(linear_to_srgb(linear) * 255.0f);
}

// The curve at the 256 values an 8-bit channel decodes to.
struct DecodeTable {
    std::array<float, 256> encoded, linear;
};

const DecodeTable& decode_table() {
    static const DecodeTable table = [] {
        DecodeTable t;
        for (int k = 0; k < 256; ++k) {
            // As OpenImageIO converts an 8-bit channel to float (k times 1/255, which differs
            // from k / 255 in the last bit for 126 of the 256 values).
            t.encoded[size_t(k)] = float(k) * (1.0f / 255.0f);
            t.linear[size_t(k)] = curve_to_linear(t.encoded[size_t(k)]);
        }
        return t;
    }();
    return table;
}

// first[k]: the smallest float in [0, 1] whose code is k or more. The code is monotonic in the
// value and non-negative floats order as their bits do, so bisection over the bits finds it.
const std::array<float, 256>& encode_thresholds() {
    static const std::array<float, 256> first = [] {
        std::array<float, 256> t{};
        for (long k = 1; k < 256; ++k) {
            uint32_t lo = std::bit_cast<uint32_t>(0.0f), hi = std::bit_cast<uint32_t>(1.0f);
            while (lo < hi) {
                const uint32_t mid = lo + (hi - lo) / 2;
                if (curve_code(std::bit_cast<float>(mid)) >= k)
                    hi = mid;
                else
                    lo = mid + 1;
            }
            t[size_t(k)] = std::bit_cast<float>(lo);
        }
        return t;
    }();
    return first;
}

// A first guess for the search above: the floats in [0, 1] cut into buckets of 2^15 ulps by
// their bits, each holding the code of its first float. A bucket spans at most 0.22 codes
// (near 1, where the curve is flattest in ulps), so the guess is at most one or two below.
struct EncodeBuckets {
    static constexpr uint32_t kShift = 15;
    static constexpr uint32_t kCount = (0x3f800000u >> kShift) + 1;  // up to 1.0f
    std::array<float, 256> first;
    std::array<uint8_t, kCount> code;
};

const EncodeBuckets& encode_buckets() {
    static const EncodeBuckets buckets = [] {
        EncodeBuckets b;
        b.first = encode_thresholds();
        for (uint32_t i = 0; i < EncodeBuckets::kCount; ++i) {
            const float start = std::bit_cast<float>(i << EncodeBuckets::kShift);
            b.code[i] = uint8_t(std::upper_bound(b.first.begin() + 1, b.first.end(), start) -
                                b.first.begin() - 1);
        }
        return b;
    }();
    return buckets;
}

}  // namespace

float srgb_to_linear(float encoded) {
    const float scaled = encoded * 255.0f;
    if (scaled >= 0.0f && scaled <= 255.0f) {
        const size_t k = size_t(scaled + 0.5f);
        const DecodeTable& t = decode_table();
        if (t.encoded[k] == encoded) return t.linear[k];
    }
    return curve_to_linear(encoded);
}

float linear_to_srgb(float linear) {
    if (linear <= 0.0031308f) return linear * 12.92f;
    return float(1.055 * std::pow(double(linear), 1.0 / 2.4) - 0.055);
}

uint8_t linear_to_srgb8(float linear) {
    // The code of the bucket's first float, then the few thresholds inside the bucket.
    const EncodeBuckets& b = encode_buckets();
    const uint32_t bits = std::bit_cast<uint32_t>(linear);
    uint32_t code = b.code[bits >> EncodeBuckets::kShift];
    while (code < 255 && linear >= b.first[code + 1]) ++code;
    return uint8_t(code);
}

}  // namespace acetate
