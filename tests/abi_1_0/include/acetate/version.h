/* Acetate SDK version: the release of these headers, for information. Compatibility is decided
 * by the plugin ABI's own version, ACETATE_ABI_VERSION in acetate/effect.h. */
#ifndef ACETATE_VERSION_H
#define ACETATE_VERSION_H

#define ACETATE_VERSION_MAJOR 0
#define ACETATE_VERSION_MINOR 1
#define ACETATE_VERSION_PATCH 0

#endif
