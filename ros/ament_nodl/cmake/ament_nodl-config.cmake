# The CMake configuration file that `pip install nodl-toolkit` installs (as
# share/ament_nodl/cmake/ament_nodlConfig.cmake). When colcon builds the ament_nodl
# package, ament_package() generates that file instead; both include the same extras.
include("${CMAKE_CURRENT_LIST_DIR}/ament_nodl-extras.cmake")
set(ament_nodl_FOUND TRUE)
