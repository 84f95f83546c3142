// BROKEN on purpose: the plugin must not end its host's process. info() calls std::exit(0), so
// the process ends, with status 0, while the host reads the descriptor. Caught by: the describe
// step, which must stop the run with "the plugin called exit(0) while describing itself" (not a
// missing plugin.json, and not the harness's own describe error); no case runs.
#include <acetate/effect.hpp>
#include <cstdlib>

class ExitsWhileDescribing final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override { std::exit(0); }
    void build(acetate::sdk::Graph&, const acetate::sdk::Floor&) const override {}
};
ACETATE_REGISTER_EFFECT(ExitsWhileDescribing)
