#include "checks.hpp"

#include <fmt/format.h>

#include <array>

namespace acetate::harness {
namespace {

constexpr std::string_view kContractCases =
    "every contract case (sizes, inputs, floors, lights, masks, params, time, frames, loads, "
    "contexts, formats, relations, combined), and on the plugin's own floors in the integration "
    "cases";

constexpr std::array kChecks = {
    CheckInfo{"premultiplied", "3", kContractCases, true, true,
              "alpha below 2^-24 with any of `r, g, b` more than 2^-24 (times the input's "
              "largest rgb/a, if above 1) from 0"},
    CheckInfo{"coverage", "2a, 2b", kContractCases, true, true,
              "preserving: alpha not bit-identical to the input's; expanding: alpha below the "
              "input's, or above 1"},
    CheckInfo{"alpha-leak", "2a, 2b", kContractCases, true, true,
              "an input pixel with alpha exactly 1 whose output alpha is below 1"},
    CheckInfo{"finite", "4", kContractCases, true, true,
              "NaN or ±Inf in any output, or in the composite of all floors"},
    CheckInfo{"non-negative", "1", kContractCases, true, true, "any channel of any output below 0"},
    CheckInfo{"reach", "2b", "every contract case, for a floor effect that declared a reach", true,
              true,
              "a pixel the effect changes past its declared reach: the same floor shaded over "
              "the whole canvas differs"},
    CheckInfo{"undefined-results", "4", "every contract case (each value of a sweep too)", true,
              true,
              "a pixel finite as compiled but not when the GLSL is compiled with checked `min`, "
              "`max`, `clamp`, `smoothstep` and `texelFetch` (NaN outside the texture)"},
    CheckInfo{"canvas-size", "8", "`relations/canvas-size` (floor effects)", true, true,
              "a channel of the plugin's floors more than one half-float unit from the same "
              "floors on a canvas grown by 61x43 pixels to the right and below (the floors are "
              "transparent within 8 pixels of those edges)"},
    CheckInfo{"camera-region", "9",
              "`relations/camera-region` (floor effects built against ABI 1.2)", true, true,
              "a channel of the plugin's output more than one half-float unit from the same "
              "scene seen through a camera whose region starts 13 and 7 pixels left of and "
              "above the canvas, where the canvas lands (the floors are transparent within 8 "
              "pixels of every edge)"},
    CheckInfo{"camera-scale", "9", "`relations/camera-scale` (floor effects built against ABI 1.2)",
              true, true,
              "a channel of the plugin's output through a camera over the whole canvas at scale "
              "1/2 outside the range the whole render takes over the 2x2 scene pixels the "
              "output pixel covers and one around them, widened by 2 half-float units and by "
              "the plugin's declared `scale_tolerance` times the range's largest magnitude"},
    CheckInfo{"format-agreement", "8", "`formats/rgba32f`", true, true,
              "a channel in rgba32f more than 8 half-float units (at the larger of the value and "
              "the input's largest) from the same scene in rgba16f"},
    CheckInfo{"process-hygiene", "7", "every case", true, true,
              "a plugin call (load, build, unload) that changed the floating-point environment, "
              "a signal disposition or the signal mask, an environment variable, the open "
              "descriptors, the number of threads, the working folder, the umask or the locale"},
    CheckInfo{"vulkan-validation", "none: no undefined behaviour in Vulkan",
              "every case but `determinism/without-layer`", true, true,
              "any warning or error of the Khronos validation layer in the case's process"},
    CheckInfo{"determinism", "5",
              "`determinism/run-1`, `determinism/run-2`, `determinism/after-history`, "
              "`determinism/without-layer`",
              true, true,
              "two frames in one process, or the outputs of two processes (one fresh, one after "
              "other loads and frames, one without the validation layer), not bit-identical; "
              "memory read before written differs between processes (poisoned)"},
    CheckInfo{"state-isolation", "6", "`isolation/state`", true, true,
              "floor 0 changed by rendering floor 1 in between; floor 1 changed by floor 0's "
              "instance; a second load rendering differently"},
    CheckInfo{"memory", "none: a plugin must not leak", "`isolation/state`", true, true,
              "after a warm-up, a frame (time advancing, the floor switching) that allocates a "
              "target, loads an image, compiles a shader or creates a pipeline; a change in the "
              "number of images held; resident memory growing by more than 1 MiB over the "
              "frames, or by more than 2 MiB over repeated loads of the scene (a leak in "
              "`build()`)"},
    CheckInfo{"floor-isolation", "6", "`isolation/floors`", true, true,
              "the effect on floor 1 changing the composite where floor 1's output has alpha 0"},
    CheckInfo{"disconnected-parameters", "none: a declared parameter must change something",
              "`params/disconnected`", true, true,
              "a parameter whose five values over its range (minimum, maximum and three between) "
              "all give bit-identical output under three settings of the others and at three "
              "times (a periodic parameter, equal at its ends, passes)"},
    CheckInfo{"cross-floor", "6", "the integration cases", true, true,
              "a floor's output in the integration stack differing from its output with the "
              "other floors' effects removed"},
    CheckInfo{"reference", "none: it guards the compositor", "the integration cases", true, true,
              "the GPU's composite of the integration stack more than one RGBA16F rounding per "
              "floor away from a double-precision CPU reference (WARN above half that)"},
    CheckInfo{"golden", "none: colour is judged against blessed references",
              "the reference cases (`reference/…`); and `reference/current` when the references "
              "were blessed for another source",
              true, true,
              "an image of a reference case further from its blessed reference than its gates "
              "allow; references blessed for another source"},
    CheckInfo{"load", "all: the host's checks at load",
              "any case whose scene the host refused to load", false, false,
              "the host refused the scene: a descriptor or parameter refused, `build()` failing, "
              "a shader not compiling"},
    CheckInfo{"run", "none: the harness's own", "any case whose child could not run it", false,
              false, "no device, the validation layer missing, an unwritable folder"},
    CheckInfo{"process", "none: a plugin must not bring down or stall its host",
              "every case (a summary row, not a check a child runs)", false, true,
              "the case's child process killed by a signal or exiting without a result (CRASH), "
              "or killed after `--timeout` seconds of CPU time, 120 by default, or four times "
              "that on the clock while waiting (TIMEOUT), twice: a case killed at the limit runs "
              "once more in a fresh process before its TIMEOUT counts"},
    CheckInfo{"repeat", "5", "every case, with `--repeat`", false, false,
              "a case whose verdict differs between its runs (FLAKY)"},
    CheckInfo{"waiver", "none: the registry's own", "`waivers/expired`", false, false,
              "a waiver past its date"},
};

}  // namespace

std::span<const CheckInfo> registered_checks() {
    return kChecks;
}

const CheckInfo* find_registered_check(std::string_view name) {
    for (const CheckInfo& c : kChecks)
        if (c.name == name) return &c;
    return nullptr;
}

std::string harness_checks_table() {
    std::string out = "| check | rule | in which cases | waivable |\n|---|---|---|---|\n";
    for (const CheckInfo& c : kChecks)
        out += fmt::format("| `{}` | {} | {} | {} |\n", c.name, c.rule, c.cases,
                           c.waivable ? "yes" : "no");
    return out;
}

std::string contract_checks_table() {
    std::string out = "| check | rule | what fails it |\n|---|---|---|\n";
    for (const CheckInfo& c : kChecks)
        if (c.in_contract) out += fmt::format("| `{}` | {} | {} |\n", c.name, c.rule, c.fails);
    return out;
}

}  // namespace acetate::harness
