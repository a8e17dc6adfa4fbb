// The higher room may use the lower one.
#include "partreg/core/high/high.hpp"
#include "low/nothing_here.hpp"
