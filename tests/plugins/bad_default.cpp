// A parameter whose default lies outside its own range.
#include <acetate/effect.hpp>

class BadDefault final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.bad_default";
        e.params = {{"strength", "out of range on purpose", 1.5f, 0.0f, 1.0f}};
        return e;
    }
    void build(acetate::sdk::Graph&, const acetate::sdk::Floor&) const override {}
};
ACETATE_REGISTER_EFFECT(BadDefault)
