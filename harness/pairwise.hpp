#pragma once
// A pairwise (strength 2) covering array: rows of factor levels such that every pair of levels
// of every two factors appears together in at least one row. Built greedily (AETG: each new
// row is the best of several candidates, each grown factor by factor choosing the level that
// covers the most pairs not yet covered), seeded, so a run's rows are reproducible.

#include <cstdint>
#include <vector>

namespace acetate::harness {

struct CoveringArray {
    std::vector<std::vector<int>> rows;  // rows[i][f] in [0, levels[f])
    uint64_t pairs = 0;                  // the pairs of levels the rows cover: all of them
};

// `levels[f]` levels for factor f (each at least 1).
CoveringArray pairwise_covering_array(const std::vector<int>& levels, uint64_t seed);

// How many pairs of levels of two different factors `rows` leave uncovered (0 for a covering
// array): what the unit test and the report check.
uint64_t uncovered_pairs(const std::vector<int>& levels, const std::vector<std::vector<int>>& rows);

}  // namespace acetate::harness
