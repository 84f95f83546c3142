// build() reports failure: it throws, and the C++ layer maps that to a status and a message.
#include <acetate/effect.hpp>
#include <stdexcept>

class BuildFails final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.build_fails";
        return e;
    }
    void build(acetate::sdk::Graph&, const acetate::sdk::Floor&) const override {
        throw std::runtime_error("the floor has no water mask to work with");
    }
};
ACETATE_REGISTER_EFFECT(BuildFails)
