/* Acetate SDK version. The plugin ABI (acetate/effect.h) arrives with the plugin runtime. */
#ifndef ACETATE_VERSION_H
#define ACETATE_VERSION_H

#define ACETATE_VERSION_MAJOR 0
#define ACETATE_VERSION_MINOR 1
#define ACETATE_VERSION_PATCH 0

#endif
