// Placeholder: the broken-plugin battery.
#include <gtest/gtest.h>
