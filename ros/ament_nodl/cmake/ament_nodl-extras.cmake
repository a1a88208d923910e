# ament_nodl: register NoDL definitions in the ament index and validate them at build time.
#
#   find_package(ament_nodl REQUIRED)
#   ament_nodl_register_interface(<name> FILE <file>)     # nodl://<package>/<name>
#   ament_nodl_register_node(<executable> FILE <file>)
#   ament_nodl_generate_cpp(<target> <definition> ...)    # the rclcpp base class, as a library
#   ament_nodl_generate_python(<definition> ...)          # the rclpy base class, installed
#   ament_nodl_doc_check(<dir> [TARGETS ...])             # test: nodl doc --check of <dir>
#
# Included by ament_nodlConfig.cmake: the one ament_package() generates when colcon builds
# the ament_nodl package (CONFIG_EXTRAS), or the one `pip install nodl-toolkit` installs.

if(_AMENT_NODL_CONFIG_INCLUDED)
  return()
endif()
set(_AMENT_NODL_CONFIG_INCLUDED TRUE)

get_filename_component(_ament_nodl_prefix "${CMAKE_CURRENT_LIST_DIR}/../../.." ABSOLUTE)
# The `nodl` command installed next to this file (pip, or a merged colcon install) wins
# over one found on PATH (an isolated colcon install: the nodl_toolkit package's bin/,
# which colcon puts on PATH for every package that depends on ament_nodl).
find_program(AMENT_NODL_EXECUTABLE nodl HINTS "${_ament_nodl_prefix}/bin" NO_DEFAULT_PATH)
if(NOT AMENT_NODL_EXECUTABLE)
  find_program(AMENT_NODL_EXECUTABLE nodl)
endif()
if(NOT AMENT_NODL_EXECUTABLE)
  message(FATAL_ERROR
    "ament_nodl: the 'nodl' command was not found (looked in ${_ament_nodl_prefix}/bin and on "
    "PATH). Build the nodl_toolkit package in the same workspace, or install the NoDL toolkit "
    "into the environment that builds this package (pip install nodl-toolkit).")
endif()

# ament_index_register_resource() comes from ament_cmake_core.
find_package(ament_cmake_core QUIET REQUIRED)
include("${CMAKE_CURRENT_LIST_DIR}/ament_nodl_register.cmake")
include("${CMAKE_CURRENT_LIST_DIR}/ament_nodl_generate.cmake")
include("${CMAKE_CURRENT_LIST_DIR}/ament_nodl_doc.cmake")
