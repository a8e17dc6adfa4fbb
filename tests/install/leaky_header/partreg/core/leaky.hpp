#pragma once
// A header that would leak Ceres to users: check_public_headers.sh must refuse it (ctest public_headers_refuse_ceres).
#include <ceres/ceres.h>
