#pragma once
// How every program (acetate, acetate-harness, acetate-bench) binds a flag that takes a
// number, a day or a person's name: CLI11 hands over the text as typed, and the project's one
// reader of such text (host/core/number_text.hpp) alone turns it into the value, so "nan",
// "-1" for an unsigned count, "2^64", "3x" and "2026-02-30" are refused the same way by all
// three. A refusal is thrown as CLI::ValidationError carrying the reader's one line
// ("--time: must be a finite number, got \"nan\""); each program catches it around its parse
// and prints that line alone, with exit status 2 (a usage error, docs/conventions.md).

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>

#include "core/number_text.hpp"

namespace acetate::flags {

// The seconds every program takes for --time: effects read the time as a 32-bit float
// (acetate_time), so it must be finite and within that float's range; negative times are
// allowed (the harness tests effects at -100 s).
inline constexpr double kMaxTimeSeconds = double(std::numeric_limits<float>::max());

namespace detail {
template <class T>
struct Unwrapped {
    using type = T;
};
template <class T>
struct Unwrapped<std::optional<T>> {
    using type = T;
};

// The option's own name for messages: the last of "-o,--output", as CLI11 names it.
inline std::string label_of(const std::string& names) {
    const size_t comma = names.rfind(',');
    return comma == std::string::npos ? names : names.substr(comma + 1);
}
}  // namespace detail

// `names` bound to `target` (an arithmetic type or std::optional of one), read within
// [min, max]. The target keeps its value when the flag is absent; help shows that value.
template <class Target, class T = typename detail::Unwrapped<Target>::type>
CLI::Option* add_number(CLI::App* app, const std::string& names, Target& target,
                        std::type_identity_t<T> min, std::type_identity_t<T> max,
                        const std::string& help) {
    const std::string label = detail::label_of(names);
    CLI::Option* option = app->add_option_function<std::string>(
        names,
        [&target, label, min, max](const std::string& text) {
            auto value = number_text::read<T>(text, label, min, max);
            if (!value) throw CLI::ValidationError(value.error().message);
            target = value.value();
        },
        help);
    option->type_name(std::is_floating_point_v<T> ? "NUMBER"
                      : std::is_signed_v<T>       ? "INT"
                                                  : "UINT");
    if constexpr (!std::is_same_v<Target, std::optional<T>>)
        option->default_str(fmt::format("{}", target));
    return option;
}

// A day YYYY-MM-DD that exists, kept as typed.
inline CLI::Option* add_day(CLI::App* app, const std::string& names, std::string& target,
                            const std::string& help) {
    const std::string label = detail::label_of(names);
    return app
        ->add_option_function<std::string>(
            names,
            [&target, label](const std::string& text) {
                auto day = number_text::day(text, label);
                if (!day) throw CLI::ValidationError(day.error().message);
                target = text;
            },
            help)
        ->type_name("YYYY-MM-DD");
}

// A person's name: not empty, not only spaces, one line.
inline CLI::Option* add_name(CLI::App* app, const std::string& names, std::string& target,
                             const std::string& help) {
    const std::string label = detail::label_of(names);
    return app
        ->add_option_function<std::string>(
            names,
            [&target, label](const std::string& text) {
                auto name = number_text::name(text, label);
                if (!name) throw CLI::ValidationError(name.error().message);
                target = name.value();
            },
            help)
        ->type_name("NAME");
}

}  // namespace acetate::flags
