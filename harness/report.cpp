// Placeholder: filled in by the report implementation.
#include "report.hpp"
