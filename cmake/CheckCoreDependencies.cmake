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
