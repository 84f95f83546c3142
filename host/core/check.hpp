#pragma once
// ACETATE_CHECK: an always-on check for contract violations (tier 2 of docs/design.md, "Errors:
// three tiers"). Unlike assert it stays in release builds; it names what was violated and
// aborts, because continuing would render something wrong without saying so.

#include <cstdio>
#include <cstdlib>

#define ACETATE_CHECK(cond, ...)                                                              \
    do {                                                                                      \
        if (!(cond)) {                                                                        \
            std::fprintf(stderr, "acetate: contract violated: %s (%s:%d): ", #cond, __FILE__, \
                         __LINE__);                                                           \
            std::fprintf(stderr, __VA_ARGS__);                                                \
            std::fprintf(stderr, "\n");                                                       \
            std::abort();                                                                     \
        }                                                                                     \
    } while (0)
