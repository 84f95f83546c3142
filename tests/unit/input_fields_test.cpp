// The input model keeps up with the scene format and the ABI (harness/input_model.hpp,
// input_fields()): every field of docs/scene-format.md's tables and every member of
// effect.h's AcetateFloorInfo, AcetateLightInfo and AcetateLight is declared, as observed (with
// a dimension and edges) or not observed (with the reason); nothing declared is gone from
// them; and every edge's case is one the planner plans. Adding a field to the format without
// a line in harness/input_fields.cpp fails here.

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "case_spec.hpp"
#include "input_model.hpp"
#include "test_files.hpp"

namespace acetate::harness {
namespace {

// "<section>.<field>" for each row of each field table in scene-format.md ("scene" for the
// top level).
std::set<std::string> scene_format_fields(const std::string& text) {
    std::set<std::string> out;
    std::istringstream in(text);
    std::string line, section;
    const std::regex heading("^## (.+)$"), row("^\\| `([a-z_]+)` \\|");
    std::smatch m;
    while (std::getline(in, line)) {
        if (std::regex_search(line, m, heading)) {
            section = m[1].str() == "Top level" ? "scene" : m[1].str();
        } else if (std::regex_search(line, m, row)) {
            out.insert(section + "." + m[1].str());
        }
    }
    return out;
}

// "<struct>.<member>" for each member of the typedef'd structs `names` in effect.h.
std::set<std::string> abi_fields(const std::string& text, const std::set<std::string>& names) {
    std::set<std::string> out;
    const std::regex open("^typedef struct (Acetate[A-Za-z]+) \\{"),
        member("^\\s+[A-Za-z_][^;/(]*[ *]([a-z_][a-z0-9_]*)(\\[[0-9]+\\])?;");
    std::istringstream in(text);
    std::string line, current;
    std::smatch m;
    while (std::getline(in, line)) {
        if (std::regex_search(line, m, open)) {
            current = names.count(m[1].str()) ? m[1].str() : "";
        } else if (line.rfind("}", 0) == 0) {
            current.clear();
        } else if (!current.empty() && std::regex_search(line, m, member)) {
            out.insert(current + "." + m[1].str());
        }
    }
    return out;
}

// A floor effect with a mask, a parameter and a preset: every kind of case is planned for it.
PluginInfo full_plugin() {
    PluginInfo p;
    p.id = "test.fields";
    p.scope = "floor";
    p.coverage = "preserving";
    p.masks = {"water"};
    ParamInfo strength;
    strength.name = "strength";
    strength.type = "float";
    strength.default_value = 0.5f;
    strength.max_value = 1.0f;
    p.params = {strength};
    p.presets = {"low"};
    return p;
}

std::string planned_id(std::string id, const PluginInfo& plugin) {
    for (const auto& [slot, value] :
         {std::pair<std::string, std::string>{"{param}", plugin.params[0].name},
          {"{preset}", plugin.presets[0]}})
        if (const size_t at = id.find(slot); at != std::string::npos)
            id.replace(at, slot.size(), value);
    return id;
}

TEST(InputFields, EveryFieldOfTheFormatAndTheAbiHasADimensionWithItsEdges) {
    const std::set<std::string> scene =
        scene_format_fields(test::read_file(ACETATE_SOURCE_DIR "/docs/scene-format.md"));
    const std::set<std::string> abi =
        abi_fields(test::read_file(ACETATE_SOURCE_DIR "/sdk/include/acetate/effect.h"),
                   {"AcetateFloorInfo", "AcetateLightInfo", "AcetateLight"});
    // The readers found the tables and the structs (a renamed heading would empty them).
    ASSERT_GE(scene.size(), 25u);
    ASSERT_TRUE(scene.count("light.height") && scene.count("sun.elevation"));
    ASSERT_GE(abi.size(), 25u);
    ASSERT_TRUE(abi.count("AcetateFloorInfo.floor_name") && abi.count("AcetateLightInfo.height"));

    std::set<std::string> schema = scene;
    schema.insert(abi.begin(), abi.end());
    std::set<std::string> dimensions;
    for (const InputDimension& d : input_dimensions()) dimensions.insert(d.name);
    std::map<std::string, const InputField*> declared;
    for (const InputField& f : input_fields()) {
        EXPECT_TRUE(declared.emplace(f.field, &f).second) << f.field << " is declared twice";
        EXPECT_TRUE(schema.count(f.field))
            << f.field << " is declared but neither scene-format.md nor effect.h has it";
        if (f.dimension.empty()) {
            EXPECT_FALSE(f.not_observed.empty()) << f.field << ": no dimension and no reason";
            EXPECT_TRUE(f.edges.empty()) << f.field;
        } else {
            EXPECT_TRUE(dimensions.count(f.dimension))
                << f.field << ": no dimension named " << f.dimension;
            EXPECT_FALSE(f.edges.empty()) << f.field << " has a dimension but no edges";
        }
    }
    for (const std::string& field : schema)
        EXPECT_TRUE(declared.count(field))
            << field << " is in the format but the input model has no dimension for it "
            << "(harness/input_fields.cpp)";

    // Every edge is tried by a planned case, at the lowest strictness and the default.
    const PluginInfo plugin = full_plugin();
    for (int strictness : {1, 5}) {
        std::set<std::string> planned;
        for (const CaseSpec& c : plan_cases(plugin, strictness, 1, true, true, {}))
            planned.insert(c.id);
        for (const InputField& f : input_fields())
            for (const InputEdge& edge : f.edges)
                EXPECT_TRUE(planned.count(planned_id(edge.case_id, plugin)))
                    << f.field << " = " << edge.value << ": no case " << edge.case_id
                    << " at strictness " << strictness;
    }
}

}  // namespace
}  // namespace acetate::harness
