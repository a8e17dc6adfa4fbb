// A lower room that reaches up: the layering check must name this file and its include.
#include "partreg/core/high/high.hpp"
#include "high/high_internal.hpp"
