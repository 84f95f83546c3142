// Placeholder: filled in with the host policy tests.
#include <gtest/gtest.h>
