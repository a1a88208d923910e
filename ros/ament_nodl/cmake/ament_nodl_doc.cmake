# Reference pages kept up to date: `nodl doc --check` as a package test.
#
#   ament_nodl_doc_check(<dir> [TARGETS <target>...] [FORMAT md|html|rst] [TIMEOUT <seconds>])
#
# Registers the test `nodl_doc_check` (with ament_add_test, so that `colcon test-result`
# reports it), when BUILD_TESTING is on.  It runs, in the package's source folder,
#
#   nodl doc <targets> -o <dir> --format <format> --check
#
# with this package's install prefix on AMENT_PREFIX_PATH, so that the package's
# registered definitions are read as installed.  It fails when a page in <dir> differs
# from what the definitions give (NODL275), is missing (NODL276), or was written for a
# node that is gone (NODL277); it writes nothing.  Write the pages with the same command
# without --check (after building the package and sourcing its install).
#
# :param dir: the folder of the pages, relative to CMAKE_CURRENT_SOURCE_DIR (rosdoc2 reads
#   the package's doc/)
# :param TARGETS: what is documented (`nodl doc` targets: PACKAGE, PACKAGE/EXECUTABLE, a
#   definition file, a launch file...); default: this package (every node it registers)
# :param FORMAT: md (default, MyST Markdown), html or rst
# :param TIMEOUT: the test's timeout in seconds (default 120)
#
function(ament_nodl_doc_check dir)
  set(_what "ament_nodl_doc_check(${dir})")
  cmake_parse_arguments(ARG "" "FORMAT;TIMEOUT" "TARGETS" ${ARGN})
  if(ARG_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "${_what}: unexpected arguments '${ARG_UNPARSED_ARGUMENTS}'; usage: "
      "ament_nodl_doc_check(<dir> [TARGETS <target>...] [FORMAT md|html|rst] [TIMEOUT <seconds>])")
  endif()
  if(NOT ARG_FORMAT)
    set(ARG_FORMAT md)
  endif()
  if(NOT ARG_FORMAT MATCHES "^(md|html|rst)$")
    message(FATAL_ERROR "${_what}: FORMAT '${ARG_FORMAT}' is not md, html or rst")
  endif()
  if(NOT ARG_TARGETS)
    set(ARG_TARGETS "${PROJECT_NAME}")
  endif()
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 120)
  endif()
  if(NOT ARG_TIMEOUT MATCHES "^[1-9][0-9]*$")
    message(FATAL_ERROR "${_what}: TIMEOUT '${ARG_TIMEOUT}' is not a number of seconds")
  endif()
  get_property(_registered GLOBAL PROPERTY _AMENT_NODL_DOC_CHECK)
  if(_registered)
    message(FATAL_ERROR "${_what}: the package already checks its pages in '${_registered}' "
      "(one ament_nodl_doc_check per package; give several TARGETS instead)")
  endif()
  set_property(GLOBAL PROPERTY _AMENT_NODL_DOC_CHECK "${dir}")
  if(DEFINED BUILD_TESTING AND NOT BUILD_TESTING)
    return()
  endif()
  get_filename_component(_dir "${dir}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
  find_package(ament_cmake_test QUIET REQUIRED)
  ament_add_test(nodl_doc_check
    COMMAND "${AMENT_NODL_EXECUTABLE}" doc ${ARG_TARGETS} -o "${_dir}" --format "${ARG_FORMAT}"
      --check
    WORKING_DIRECTORY "${CMAKE_CURRENT_SOURCE_DIR}"
    APPEND_ENV "AMENT_PREFIX_PATH=${CMAKE_INSTALL_PREFIX}"
    GENERATE_RESULT_FOR_RETURN_CODE_ZERO
    TIMEOUT "${ARG_TIMEOUT}")
endfunction()
