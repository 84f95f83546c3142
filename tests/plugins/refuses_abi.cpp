// An entry point that cannot serve the host's ABI version.
#include <acetate/effect.h>

extern "C" ACETATE_EXPORT AcetateStatus acetate_effect_entry_v1(uint32_t,
                                                                const AcetateEffectApi**) {
    return ACETATE_ERROR_UNSUPPORTED_ABI;
}
