# ament_nodl: register NoDL definitions in the ament index and validate them at build time.
#
#   find_package(ament_nodl REQUIRED)
#   ament_nodl_register_interface(<name> FILE <file>)     # nodl://<package>/<name>
#   ament_nodl_register_node(<executable> FILE <file>)
#
# Installed by the NoDL toolkit (pip install nodl-toolkit) into <prefix>/share/ament_nodl/cmake.

if(_AMENT_NODL_CONFIG_INCLUDED)
  return()
endif()
set(_AMENT_NODL_CONFIG_INCLUDED TRUE)

get_filename_component(_ament_nodl_prefix "${CMAKE_CURRENT_LIST_DIR}/../../.." ABSOLUTE)
# The `nodl` command installed next to this file wins over one found on PATH.
find_program(AMENT_NODL_EXECUTABLE nodl HINTS "${_ament_nodl_prefix}/bin" NO_DEFAULT_PATH)
if(NOT AMENT_NODL_EXECUTABLE)
  find_program(AMENT_NODL_EXECUTABLE nodl)
endif()
if(NOT AMENT_NODL_EXECUTABLE)
  message(FATAL_ERROR
    "ament_nodl: the 'nodl' command was not found (looked in ${_ament_nodl_prefix}/bin and on "
    "PATH). Install the NoDL toolkit into the environment that builds this package.")
endif()

include("${CMAKE_CURRENT_LIST_DIR}/ament_nodl_register.cmake")
set(ament_nodl_FOUND TRUE)
