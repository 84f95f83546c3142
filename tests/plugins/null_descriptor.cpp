// A function table whose descriptor is NULL.
#include <acetate/effect.h>

static AcetateStatus build(const AcetateHostApi*, AcetateGraph*, const AcetateFloorInfo*) {
    return ACETATE_OK;
}
static const char* last_error() {
    return nullptr;
}
static const AcetateEffectApi kApi = {sizeof(AcetateEffectApi), nullptr, &build, &last_error};

extern "C" ACETATE_EXPORT AcetateStatus acetate_effect_entry_v1(uint32_t,
                                                                const AcetateEffectApi** out) {
    *out = &kApi;
    return ACETATE_OK;
}
