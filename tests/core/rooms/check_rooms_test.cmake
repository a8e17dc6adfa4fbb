# The core's layering check run on a two-room tree whose lower room includes the higher one: it must fail,
# naming the file and the include (ctest core_rooms_refuse_upward_include matches the message).
# Usage: cmake -DPROJECT_SOURCE_DIR=<partreg> -P check_rooms_test.cmake
cmake_minimum_required(VERSION 3.22)
include(${PROJECT_SOURCE_DIR}/cmake/CheckCoreDependencies.cmake)
partreg_core_room(base)
partreg_core_room(low USES base)
partreg_core_room(high USES base low)
partreg_check_core_rooms(${CMAKE_CURRENT_LIST_DIR}/core)
