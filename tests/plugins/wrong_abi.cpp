// Declares a descriptor built for ABI version 2, which this host does not speak.
#include <acetate/effect.h>

static const AcetateEffectDescriptor kDescriptor = {sizeof(AcetateEffectDescriptor),
                                                    2u,
                                                    "test.wrong_abi",
                                                    "Wrong ABI",
                                                    1,
                                                    0,
                                                    0,
                                                    ACETATE_SCOPE_FLOOR,
                                                    ACETATE_COVERAGE_PRESERVING,
                                                    nullptr,
                                                    0,
                                                    nullptr,
                                                    0,
                                                    nullptr,
                                                    0,
                                                    ""};
static AcetateStatus build(const AcetateHostApi*, AcetateGraph*, const AcetateFloorInfo*) {
    return ACETATE_OK;
}
static const char* last_error() {
    return nullptr;
}
static const AcetateEffectApi kApi = {sizeof(AcetateEffectApi), &kDescriptor, &build, &last_error};

extern "C" ACETATE_EXPORT AcetateStatus acetate_effect_entry_v1(uint32_t,
                                                                const AcetateEffectApi** out) {
    *out = &kApi;
    return ACETATE_OK;
}
