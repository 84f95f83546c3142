#pragma once
// The input model: every input a plugin can observe through the ABI, as dimensions with the
// values the harness tries (docs/harness.md, "The input model"). The planner varies each
// dimension on its own and draws combinations from a Latin hypercube over all of them; the
// fuzzer draws from the same space and shrinks toward its simplest point.

#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "case_spec.hpp"

namespace acetate::harness {

// One dimension, as the report and the docs list it.
struct InputDimension {
    std::string name;  // "canvas", "lights", ...
    std::string what;  // one line: what the plugin observes
};
const std::vector<InputDimension>& input_dimensions();

// A boundary value of a field and the planned case that tries it. In `case_id`, "{param}" and
// "{preset}" stand for the plugin's first parameter and preset.
struct InputEdge {
    std::string value;    // "0", "300 characters", "elevation 90"
    std::string case_id;  // "lights/on-the-floor"
};
// A field of the scene format (docs/scene-format.md, "<section>.<field>", the top level's as
// "scene.<field>") or of what build() is given (effect.h, "<struct>.<member>"), and how the
// model covers it: the dimension it belongs to and its edges, or why no plugin can observe
// it. tests/unit/input_fields_test.cpp reads both files and fails on a field missing here, a
// field here that they no longer have, an observed field without edges, and an edge whose
// case the planner does not plan.
struct InputField {
    std::string field;
    std::string dimension;  // one of input_dimensions(); empty when not observed
    std::vector<InputEdge> edges;
    std::string not_observed;  // why a plugin cannot observe it
};
const std::vector<InputField>& input_fields();

// This case's value of every dimension (the `inputs` the report tabulates). Values the planner
// already set (params) are kept.
std::map<std::string, std::string> describe_inputs(const CaseSpec& spec, const PluginInfo& plugin);

// `points` points in [0, 1)^`dimensions`, stratified: along every axis each of the `points`
// equal intervals holds exactly one point (McKay's Latin hypercube), seeded.
std::vector<std::vector<double>> latin_hypercube(size_t points, size_t dimensions, uint64_t seed);

// How many unit coordinates scenario_at() reads for this plugin.
size_t scenario_dimensions(const PluginInfo& plugin);
// A contract case at unit coordinates `u` of the whole model: canvas (1 to 300 by 1 to 200,
// log-spaced), floors (1 to 4), the floor the plugin is on, pixels, lights, masks, time
// (-100 s to 10^5 s), frames, prior loads, the floors' names and tiles, and every parameter
// over its range.
void scenario_at(const PluginInfo& plugin, std::span<const double> u, CaseSpec& spec);

// Values of a parameter across its range, ends included: `points` of them, evenly spaced,
// rounded for int parameters (duplicates dropped), {min, max} for bool.
std::vector<float> sweep_values(const ParamInfo& param, int points);

}  // namespace acetate::harness
