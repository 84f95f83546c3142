#pragma once
// Wall-clock time since a start point, in milliseconds (steady clock): what load and frame
// statistics and the benchmarks report.

#include <chrono>

namespace acetate {

inline double milliseconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

}  // namespace acetate
