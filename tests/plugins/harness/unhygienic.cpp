// BROKEN on purpose: a plugin call must leave the process it runs in as it found it
// (docs/contract.md, rule 7). Its build() breaks the rule named by $ACETATE_TEST_HYGIENE_RULE,
// as real plugins do by accident (a rounding mode set for its own maths, a handler installed,
// a descriptor or a thread left behind). Without the variable it is correct. The effect itself
// darkens the colour and keeps alpha.
// Caught by: PROCESS-HYGIENE only, naming the change, the call and the plugin
// (tests/harness/harness_hygiene_test.cpp).
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <acetate/effect.hpp>
#include <cfenv>
#include <chrono>
#include <clocale>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#if defined(__x86_64__)
#include <xmmintrin.h>
#endif

namespace {

std::string rule() {
    const char* value = std::getenv("ACETATE_TEST_HYGIENE_RULE");
    return value ? value : "";
}

void on_signal(int) {}

void break_rule(const std::string& which) {
    if (which == "rounding") std::fesetround(FE_TOWARDZERO);
#if defined(__x86_64__)
    if (which == "flush-to-zero") _mm_setcsr(_mm_getcsr() | 0x8040u);
#endif
    if (which == "signal") ::signal(SIGUSR1, on_signal);
    if (which == "block-signal") {
        sigset_t set;
        sigemptyset(&set);
        sigaddset(&set, SIGUSR2);
        ::pthread_sigmask(SIG_BLOCK, &set, nullptr);
    }
    if (which == "environment") ::setenv("ACETATE_TEST_LEFT_BEHIND", "1", 1);
    if (which == "descriptor") (void)::open("/dev/null", O_RDONLY);
    if (which == "thread")
        std::thread([] { std::this_thread::sleep_for(std::chrono::hours(1)); }).detach();
    if (which == "folder") (void)::chdir("/");
    if (which == "umask") ::umask(077);
    if (which == "locale") std::setlocale(LC_ALL, "C.UTF-8");
}

}  // namespace

class Unhygienic final : public acetate::sdk::Effect {
  public:
    acetate::sdk::EffectInfo info() const override {
        acetate::sdk::EffectInfo e;
        e.id = "test.harness.unhygienic";
        e.display_name = "Harness: leaves the process changed";
        e.version_major = 1, e.version_minor = 0, e.version_patch = 0;
        e.coverage = ACETATE_COVERAGE_PRESERVING;
        return e;
    }
    void build(acetate::sdk::Graph& graph, const acetate::sdk::Floor&) const override {
        break_rule(rule());
        graph.pass({.name = "darken",
                    .glsl = R"(
void main() {
    vec4 prev = texelFetch(previous, ivec2(gl_FragCoord.xy), 0);
    out_color = vec4(prev.rgb * 0.9, prev.a);
}
)",
                    .inputs = {"previous"}});
    }
};
ACETATE_REGISTER_EFFECT(Unhygienic)
