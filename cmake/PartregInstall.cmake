# cmake --install: the libraries (partreg::core, ::io, ::eval, ::render), their public headers under
# include/partreg/ with the generated partreg/version.hpp, the CMake package (partregConfig.cmake, its version
# file and the exported targets), partreg.pc, the two executables and the docs. Shaders are embedded in
# partreg_render, so nothing else is needed at run time.
include(CMakePackageConfigHelpers)

set(PARTREG_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/partreg CACHE STRING "Where partregConfig.cmake is installed")

# The exported libraries, in dependency order. partreg_glad is partreg_render's private GL loader: static,
# it has to travel with a static partreg_render.
set(partreg_libraries partreg_core)
set(partreg_header_dirs ${PROJECT_SOURCE_DIR}/core/core/include)
if(TARGET partreg_io)
  list(APPEND partreg_libraries partreg_io)
  list(APPEND partreg_header_dirs ${PROJECT_SOURCE_DIR}/core/io/include)
endif()
if(TARGET partreg_eval)
  list(APPEND partreg_libraries partreg_eval)
  list(APPEND partreg_header_dirs ${PROJECT_SOURCE_DIR}/core/eval/include)
endif()
if(TARGET partreg_render)
  list(APPEND partreg_libraries partreg_render partreg_glad)
  list(APPEND partreg_header_dirs ${PROJECT_SOURCE_DIR}/ui/render/include ${PROJECT_SOURCE_DIR}/ui/context/include)
endif()

install(TARGETS ${partreg_libraries} EXPORT partregTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
foreach(dir IN LISTS partreg_header_dirs)
  install(DIRECTORY ${dir}/partreg DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.hpp")
endforeach()
install(FILES ${PARTREG_GENERATED_INCLUDE_DIR}/partreg/version.hpp DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/partreg)

install(EXPORT partregTargets NAMESPACE partreg:: DESTINATION ${PARTREG_CMAKE_DIR})
# A static library's private dependencies become the consumer's link dependencies: the config file finds
# exactly those (shared libraries carry them themselves).
if(BUILD_SHARED_LIBS)
  set(PARTREG_STATIC_LIBRARIES OFF)
else()
  set(PARTREG_STATIC_LIBRARIES ON)
endif()
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/partregConfig.cmake.in
  ${PROJECT_BINARY_DIR}/partregConfig.cmake INSTALL_DESTINATION ${PARTREG_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/partregConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/partregConfig.cmake ${PROJECT_BINARY_DIR}/partregConfigVersion.cmake
  DESTINATION ${PARTREG_CMAKE_DIR})

# pkg-config: one partreg.pc for the whole library (link order: render, eval, io, core).
set(PARTREG_PC_LIBS "")
# Ceres's inline code (autodiff, its CHECK macros) calls glog directly.
set(PARTREG_PC_PRIVATE "-lceres -lglog")
set(PARTREG_PC_REQUIRES_PRIVATE "")
if(TARGET partreg_render)
  string(APPEND PARTREG_PC_LIBS " -lpartreg_render -lpartreg_glad")
  string(APPEND PARTREG_PC_REQUIRES_PRIVATE " osmesa")
  set(PARTREG_PC_PRIVATE "${PARTREG_PC_PRIVATE} -l${CMAKE_DL_LIBS}")
endif()
if(TARGET partreg_eval)
  string(APPEND PARTREG_PC_LIBS " -lpartreg_eval")
  string(APPEND PARTREG_PC_REQUIRES_PRIVATE " cairo tbb")
  string(APPEND PARTREG_PC_PRIVATE " -lembree3")
endif()
if(TARGET partreg_io)
  string(APPEND PARTREG_PC_LIBS " -lpartreg_io")
  # Not PCL's own pcl_io.pc: it requires OpenNI's .pc files, which Debian's libpcl-dev does not pull in.
  string(APPEND PARTREG_PC_REQUIRES_PRIVATE " assimp")
  string(APPEND PARTREG_PC_PRIVATE " -lpcl_io -lpcl_common")
  # VTK's XML I/O for .vtp files (vtk_io.cpp); Debian's VTK 9.1 ships no .pc files.
  foreach(vtk_module IN ITEMS IOXML IOXMLParser IOCore CommonDataModel CommonCore)
    string(APPEND PARTREG_PC_PRIVATE " -lvtk${vtk_module}-${PARTREG_VTK_VERSION}")
  endforeach()
endif()
string(APPEND PARTREG_PC_LIBS " -lpartreg_core")
if(NOT BUILD_SHARED_LIBS)
  # Static archives: their dependencies go on the consumer's plain link line.
  set(PARTREG_PC_LIBS "${PARTREG_PC_LIBS} ${PARTREG_PC_PRIVATE}")
  set(PARTREG_PC_REQUIRES "eigen3 nlohmann_json ${PARTREG_PC_REQUIRES_PRIVATE}")
  set(PARTREG_PC_REQUIRES_PRIVATE "")
  set(PARTREG_PC_PRIVATE "")
else()
  set(PARTREG_PC_REQUIRES "eigen3 nlohmann_json")
endif()
# The prefix is found from the .pc file's own place, so `cmake --install --prefix P` needs no reconfigure.
file(RELATIVE_PATH PARTREG_PC_TO_PREFIX ${CMAKE_INSTALL_FULL_LIBDIR}/pkgconfig ${CMAKE_INSTALL_PREFIX})
configure_file(${PROJECT_SOURCE_DIR}/cmake/partreg.pc.in ${PROJECT_BINARY_DIR}/partreg.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/partreg.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

foreach(executable partreg partreg-gui)
  if(TARGET ${executable})
    install(TARGETS ${executable} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  endif()
endforeach()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
