// Placeholder: stage transitions through the CLI.
#include <gtest/gtest.h>
