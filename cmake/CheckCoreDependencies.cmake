# partreg_core must stay a registration library: Eigen, Ceres and nanoflann.
# This check fails the configure step when anything GUI-, rendering- or file-format-related leaks
# into its link interface, so the layering (core below io, eval, ui and app) cannot erode silently.
function(partreg_check_core_dependencies target)
  set(forbidden "GL|glfw|OSMesa|imgui|vtk|VTK|pcl|PCL|assimp|cairo|embree")
  foreach(property LINK_LIBRARIES INTERFACE_LINK_LIBRARIES)
    get_target_property(libraries ${target} ${property})
    if(libraries)
      foreach(library IN LISTS libraries)
        if(library MATCHES "${forbidden}")
          message(FATAL_ERROR "${target} links '${library}': the core may only use Eigen, Ceres and nanoflann")
        endif()
      endforeach()
    endif()
  endforeach()
endfunction()

# Inside partreg_core the same holds between its rooms (one folder per concept: src/<room>/ with its public
# headers in include/partreg/core/<room>/; the base room is the top of both). core/core/CMakeLists.txt
# declares each room once, lowest first, with the rooms it may include:
#
#   partreg_core_room(geometry USES base)
#
# A room may name only rooms declared before it, so the rooms cannot form a cycle.
# partreg_check_core_rooms() then reads every #include of every file in the rooms and fails the configure
# step, naming the file and the include, when a room includes one it does not use.
function(partreg_core_room room)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "" "USES")
  get_property(declared GLOBAL PROPERTY PARTREG_CORE_ROOMS)
  if(room IN_LIST declared)
    message(FATAL_ERROR "core room '${room}' is declared twice")
  endif()
  foreach(used IN LISTS arg_USES)
    if(NOT used IN_LIST declared)
      message(FATAL_ERROR "core room '${room}' uses '${used}', which is not declared before it: "
                          "a room may use only lower rooms (declared above it), so that no cycle can form")
    endif()
  endforeach()
  set_property(GLOBAL APPEND PROPERTY PARTREG_CORE_ROOMS ${room})
  set_property(GLOBAL PROPERTY PARTREG_CORE_ROOM_${room}_USES ${arg_USES})
endfunction()

# The folder of `room` under `root` (src or include/partreg/core): the base room is the top itself.
function(_partreg_room_dir root room out)
  if(room STREQUAL "base")
    set(${out} ${root} PARENT_SCOPE)
  else()
    set(${out} ${root}/${room} PARENT_SCOPE)
  endif()
endfunction()

# The room an include line of a file in `dir` reaches, or "" for one outside partreg_core (the standard
# library, Eigen, Ceres, nanoflann). Anything else of partreg's is reported as "above the core".
function(_partreg_included_room core_dir dir target rooms out)
  set(room "")
  if(target MATCHES "^partreg/core/([a-z_0-9]+)/")
    set(room ${CMAKE_MATCH_1})
  elseif(target MATCHES "^partreg/core/[^/]+$" OR target STREQUAL "partreg/version.hpp")
    set(room base)
  elseif(target MATCHES "^partreg/")
    set(room "above the core")
  elseif(target MATCHES "^([a-z_0-9]+)/[^/]+$" AND CMAKE_MATCH_1 IN_LIST rooms)
    set(room ${CMAKE_MATCH_1})  # a room's internal header, from the src folder
  elseif(EXISTS ${dir}/${target})
    set(room same)
  elseif(EXISTS ${core_dir}/src/${target})
    set(room base)
  endif()
  set(${out} "${room}" PARENT_SCOPE)
endfunction()

# Checks every file of the declared rooms under `core_dir` (core/core) and sets partreg_core_<room>_sources,
# the room's .cpp files, in the caller's scope.
function(partreg_check_core_rooms core_dir)
  get_property(rooms GLOBAL PROPERTY PARTREG_CORE_ROOMS)
  set(problems "")
  # A new source re-runs the configure step (and so this check); cmake -P (the check's own test) cannot.
  if(CMAKE_SCRIPT_MODE_FILE)
    set(depends "")
  else()
    set(depends CONFIGURE_DEPENDS)
  endif()
  # A folder that is no declared room would escape the check.
  file(GLOB folders LIST_DIRECTORIES true ${core_dir}/src/* ${core_dir}/include/partreg/core/*)
  foreach(folder IN LISTS folders)
    get_filename_component(name ${folder} NAME)
    if(IS_DIRECTORY ${folder} AND NOT name IN_LIST rooms)
      file(RELATIVE_PATH shown ${PROJECT_SOURCE_DIR} ${folder})
      list(APPEND problems "${shown} is not a declared room")
    endif()
  endforeach()
  foreach(room IN LISTS rooms)
    get_property(uses GLOBAL PROPERTY PARTREG_CORE_ROOM_${room}_USES)
    _partreg_room_dir(${core_dir}/src ${room} source_dir)
    _partreg_room_dir(${core_dir}/include/partreg/core ${room} header_dir)
    file(GLOB sources ${depends} ${source_dir}/*.cpp)
    file(GLOB files ${depends} ${source_dir}/*.cpp ${source_dir}/*.hpp ${header_dir}/*.hpp)
    list(LENGTH sources count)
    if(count GREATER 15)
      list(APPEND problems "${source_dir} holds ${count} sources (at most 15 per room): split the room")
    endif()
    foreach(file IN LISTS files)
      get_filename_component(dir ${file} DIRECTORY)
      file(RELATIVE_PATH shown ${PROJECT_SOURCE_DIR} ${file})
      file(STRINGS ${file} lines REGEX "^[ \t]*#[ \t]*include[ \t]*[\"<]")
      foreach(line IN LISTS lines)
        string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*[\"<]([^\">]+)[\">].*$" "\\1" target "${line}")
        _partreg_included_room(${core_dir} ${dir} "${target}" "${rooms}" included)
        if(included STREQUAL "" OR included STREQUAL "same" OR included STREQUAL room)
          continue()
        elseif(included IN_LIST uses)
          continue()
        endif()
        if(included IN_LIST rooms)
          set(allowed "${uses}")
          if(NOT allowed)
            set(allowed "nothing")
          endif()
          string(REPLACE ";" ", " allowed "${allowed}")
          list(APPEND problems "${shown} includes \"${target}\" (room ${included}), but the room ${room} may "
                               "include only ${allowed}")
        else()
          list(APPEND problems "${shown} includes \"${target}\" (${included}): partreg_core includes only "
                               "its own rooms")
        endif()
      endforeach()
    endforeach()
    set(partreg_core_${room}_sources ${sources} PARENT_SCOPE)
  endforeach()
  if(problems)
    list(JOIN problems "\n  " text)
    message(FATAL_ERROR "partreg_core's rooms break their declared layering "
                        "(core/core/CMakeLists.txt, partreg_core_room):\n  ${text}")
  endif()
endfunction()
