#include "pairwise.hpp"

#include <algorithm>
#include <numeric>
#include <random>

namespace acetate::harness {
namespace {

// Which pairs are covered: one flag per (factor f, level a, factor g > f, level b).
class PairTable {
  public:
    explicit PairTable(const std::vector<int>& levels) : levels_(levels) {
        const size_t n = levels.size();
        offset_.assign(n * n, 0);
        for (size_t f = 0; f < n; ++f)
            for (size_t g = f + 1; g < n; ++g) {
                offset_[f * n + g] = size_t(total_);
                total_ += uint64_t(levels[f]) * uint64_t(levels[g]);
            }
        covered_.assign(size_t(total_), false);
        left_ = total_;
    }
    bool covered(size_t f, int a, size_t g, int b) const { return covered_[index(f, a, g, b)]; }
    void cover(const std::vector<int>& row) {
        for (size_t f = 0; f < row.size(); ++f)
            for (size_t g = f + 1; g < row.size(); ++g) {
                const size_t i = index(f, row[f], g, row[g]);
                if (!covered_[i]) {
                    covered_[i] = true;
                    --left_;
                }
            }
    }
    uint64_t total() const { return total_; }
    uint64_t left() const { return left_; }
    // A pair not yet covered, for seeding a row: its factors and levels.
    bool first_uncovered(size_t& f, int& a, size_t& g, int& b) const {
        const size_t n = levels_.size();
        for (f = 0; f < n; ++f)
            for (g = f + 1; g < n; ++g)
                for (a = 0; a < levels_[f]; ++a)
                    for (b = 0; b < levels_[g]; ++b)
                        if (!covered(f, a, g, b)) return true;
        return false;
    }

  private:
    size_t index(size_t f, int a, size_t g, int b) const {
        if (f > g) {
            std::swap(f, g);
            std::swap(a, b);
        }
        return offset_[f * levels_.size() + g] + size_t(a) * size_t(levels_[g]) + size_t(b);
    }
    std::vector<int> levels_;
    std::vector<size_t> offset_;
    std::vector<bool> covered_;
    uint64_t total_ = 0, left_ = 0;
};

}  // namespace

CoveringArray pairwise_covering_array(const std::vector<int>& levels, uint64_t seed) {
    CoveringArray out;
    const size_t n = levels.size();
    if (n == 0) return out;
    PairTable table(levels);
    out.pairs = table.total();
    if (n == 1) {  // no pairs: each level once
        for (int a = 0; a < levels[0]; ++a) out.rows.push_back({a});
        return out;
    }
    std::mt19937_64 rng(seed);
    constexpr int kCandidates = 24;
    while (table.left() > 0) {
        size_t f0 = 0, g0 = 0;
        int a0 = 0, b0 = 0;
        table.first_uncovered(f0, a0, g0, b0);
        std::vector<int> best;
        uint64_t best_gain = 0;
        for (int candidate = 0; candidate < kCandidates; ++candidate) {
            std::vector<int> row(n, -1);
            row[f0] = a0;
            row[g0] = b0;
            std::vector<size_t> order(n);
            std::iota(order.begin(), order.end(), size_t(0));
            std::shuffle(order.begin(), order.end(), rng);
            for (size_t f : order) {
                if (row[f] >= 0) continue;
                // The level covering the most new pairs with the factors set so far; ties drawn.
                int chosen = 0;
                int chosen_gain = -1;
                std::vector<int> tied;
                for (int a = 0; a < levels[f]; ++a) {
                    int gain = 0;
                    for (size_t g = 0; g < n; ++g)
                        if (g != f && row[g] >= 0 && !table.covered(f, a, g, row[g])) ++gain;
                    if (gain > chosen_gain) {
                        chosen_gain = gain;
                        tied.assign(1, a);
                    } else if (gain == chosen_gain) {
                        tied.push_back(a);
                    }
                }
                chosen = tied[std::uniform_int_distribution<size_t>(0, tied.size() - 1)(rng)];
                row[f] = chosen;
            }
            uint64_t gain = 0;
            for (size_t f = 0; f < n; ++f)
                for (size_t g = f + 1; g < n; ++g) gain += !table.covered(f, row[f], g, row[g]);
            if (gain > best_gain) {
                best_gain = gain;
                best = std::move(row);
            }
        }
        table.cover(best);
        out.rows.push_back(std::move(best));
    }
    return out;
}

uint64_t uncovered_pairs(const std::vector<int>& levels,
                         const std::vector<std::vector<int>>& rows) {
    PairTable table(levels);
    for (const std::vector<int>& row : rows) table.cover(row);
    return table.left();
}

}  // namespace acetate::harness
