// Placeholder: filled in with the report tests.
#include <gtest/gtest.h>
