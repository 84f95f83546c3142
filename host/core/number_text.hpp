#pragma once
// The one reader of values typed as text: every number, day and name a program takes on its
// command line (acetate, acetate-harness, acetate-bench) and every day the registry stores.
// The text must be exactly the value: no sign '+', no spaces, no trailing characters ("3x"),
// no hexadecimal; a number must be finite and within the caller's [min, max], an integer must
// fit its type (never wrapped: "-1" is not 18446744073709551615), a day must exist
// (2026-02-30 does not). Failures are one line worded as json_fields.hpp words a JSON field:
//   `--time: must be a finite number, got "nan"`
//   `--fail: must be at least 0, got -1`
//   `--shuffle-seed: must be at most 18446744073709551615, got 18446744073709551616`
//   `--until: must be a day that exists, got 2026-02-30 (February 2026 has 28 days)`

#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <type_traits>

#include "core/result.hpp"

namespace acetate::number_text {

// A finite decimal number ("2.5", "-1e3", "0.125") within [min, max].
Result<double> finite_number(std::string_view text, std::string_view label, double min, double max);
// A decimal integer ("42", "-7") within [min, max].
Result<int64_t> integer(std::string_view text, std::string_view label, int64_t min, int64_t max);
// A non-negative decimal integer within [min, max]; "-1" is refused, never wrapped.
Result<uint64_t> unsigned_integer(std::string_view text, std::string_view label, uint64_t min,
                                  uint64_t max);

// A calendar day of the proleptic Gregorian calendar.
struct Day {
    int year = 0, month = 0, day = 0;
};
// YYYY-MM-DD that exists: 2024-02-29 does, 2026-02-30 and 2100-02-29 do not.
Result<Day> day(std::string_view text, std::string_view label);
int days_in_month(int year, int month);

// A person's name (--by, --reviewer): not empty, not only spaces, no control characters (a
// name is printed inside one-line messages and the registry's readable copy).
Result<std::string> name(std::string_view text, std::string_view label);

// The reader for an arithmetic type T, its range that of T unless narrowed: the flag helpers
// use this, so a flag's value is read by its target's own type.
template <class T>
Result<T> read(std::string_view text, std::string_view label,
               T min = std::numeric_limits<T>::lowest(), T max = std::numeric_limits<T>::max()) {
    static_assert(std::is_arithmetic_v<T> && !std::is_same_v<T, bool>);
    if constexpr (std::is_floating_point_v<T>) {
        auto value = finite_number(text, label, double(min), double(max));
        if (!value) return value.error();
        return T(value.value());
    } else if constexpr (std::is_signed_v<T>) {
        auto value = integer(text, label, int64_t(min), int64_t(max));
        if (!value) return value.error();
        return T(value.value());
    } else {
        auto value = unsigned_integer(text, label, uint64_t(min), uint64_t(max));
        if (!value) return value.error();
        return T(value.value());
    }
}

}  // namespace acetate::number_text
