// A pass given as SPIR-V instead of GLSL. The module is compiled by the test (with the host's
// own declarations) and handed over through ACETATE_TEST_SPIRV_FILE, standing in for SPIR-V a
// plugin would ship compiled.
#include <acetate/effect.hpp>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <vector>

class SpirvPass final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.spirv_pass";
        e.params = {{"gain", "multiplies colour", 0.5f, 0.0f, 1.0f}};
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        const char* file = std::getenv("ACETATE_TEST_SPIRV_FILE");
        if (!file) throw std::runtime_error("ACETATE_TEST_SPIRV_FILE is not set");
        std::ifstream in(file, std::ios::binary);
        const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), {});
        if (bytes.empty() || bytes.size() % 4) throw std::runtime_error("not a SPIR-V module");
        std::vector<uint32_t> words(bytes.size() / 4);
        std::memcpy(words.data(), bytes.data(), bytes.size());
        graph.pass({.name = "gain", .inputs = {"previous"}, .spirv = words});
    }
};
ACETATE_REGISTER_EFFECT(SpirvPass)
