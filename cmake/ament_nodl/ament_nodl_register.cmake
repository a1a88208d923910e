# Registration of NoDL definitions.
#
# Each registered file is
#  * validated when the package builds (kind enforced, mixin references resolved), so a
#    wrong file fails the build of its own package with FILE:LINE:COL diagnostics;
#  * installed to share/<package>/nodl/;
#  * registered in the ament index: resource type nodl_nodes or nodl_interfaces, resource
#    name <package>__<key>, content the installed path relative to share/<package>.

#
# Register the node definition of an executable of this package.
#
# :param executable: the executable the definition describes
# :param FILE: the node definition (YAML or JSON), relative to CMAKE_CURRENT_SOURCE_DIR
#
function(ament_nodl_register_node executable)
  _ament_nodl_register(node nodl_nodes "${executable}" ${ARGN})
endfunction()

#
# Register a reusable interface definition, referenced as nodl://<package>/<name>.
#
# :param name: the name other node definitions use in nodl://<package>/<name>
# :param FILE: the interface definition (YAML or JSON), relative to CMAKE_CURRENT_SOURCE_DIR
#
function(ament_nodl_register_interface name)
  _ament_nodl_register(interface nodl_interfaces "${name}" ${ARGN})
endfunction()

function(_ament_nodl_register kind resource_type key)
  set(_what "ament_nodl_register_${kind}(${key})")
  cmake_parse_arguments(ARG "" "FILE" "" ${ARGN})
  if(ARG_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "${_what}: unexpected arguments '${ARG_UNPARSED_ARGUMENTS}'; "
      "usage: ament_nodl_register_${kind}(<key> FILE <file>)")
  endif()
  if(NOT ARG_FILE)
    message(FATAL_ERROR "${_what}: FILE <file> is required")
  endif()
  if(NOT key MATCHES "^[A-Za-z0-9_][A-Za-z0-9_.-]*$")
    message(FATAL_ERROR "${_what}: '${key}' is not a valid name (letters, digits, '_', '.', '-')")
  endif()
  get_filename_component(_file "${ARG_FILE}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
  if(NOT EXISTS "${_file}")
    message(FATAL_ERROR "${_what}: file '${_file}' does not exist")
  endif()
  get_filename_component(_name "${_file}" NAME)

  get_property(_keys GLOBAL PROPERTY _AMENT_NODL_KEYS_${resource_type})
  if(key IN_LIST _keys)
    message(FATAL_ERROR "${_what}: '${key}' is already registered in this package")
  endif()
  set_property(GLOBAL APPEND PROPERTY _AMENT_NODL_KEYS_${resource_type} "${key}")
  get_property(_installed GLOBAL PROPERTY _AMENT_NODL_INSTALLED)
  foreach(_entry IN LISTS _installed)
    string(REPLACE "|" ";" _pair "${_entry}")
    list(GET _pair 0 _other_name)
    list(GET _pair 1 _other_file)
    if(_other_name STREQUAL _name AND NOT _other_file STREQUAL _file)
      message(FATAL_ERROR "${_what}: '${_file}' and '${_other_file}' would both be installed "
        "as share/${PROJECT_NAME}/nodl/${_name}; rename one")
    endif()
  endforeach()
  set_property(GLOBAL APPEND PROPERTY _AMENT_NODL_INSTALLED "${_name}|${_file}")

  # A staging index in the build folder lets build-time validation resolve
  # nodl://<this package>/<name> before the package is installed.
  set(_stage "${CMAKE_BINARY_DIR}/ament_nodl_stage")
  file(WRITE "${_stage}/share/ament_index/resource_index/packages/${PROJECT_NAME}" "")
  file(WRITE "${_stage}/share/ament_index/resource_index/${resource_type}/${PROJECT_NAME}__${key}"
    "${_file}")
  if(WIN32)
    set(_sep "\\;")
  else()
    set(_sep ":")
  endif()
  set(_prefixes "${_stage}")
  if(NOT "$ENV{AMENT_PREFIX_PATH}" STREQUAL "")
    set(_prefixes "${_stage}${_sep}$ENV{AMENT_PREFIX_PATH}")
  endif()

  string(MAKE_C_IDENTIFIER "${key}" _target_key)
  set(_stamp "${CMAKE_CURRENT_BINARY_DIR}/ament_nodl/${resource_type}/${_target_key}.valid")
  file(MAKE_DIRECTORY "${CMAKE_CURRENT_BINARY_DIR}/ament_nodl/${resource_type}")
  add_custom_command(
    OUTPUT "${_stamp}"
    COMMAND "${CMAKE_COMMAND}" -E env "AMENT_PREFIX_PATH=${_prefixes}"
      "${AMENT_NODL_EXECUTABLE}" validate --kind ${kind} --resolve --quiet --stderr "${_file}"
    COMMAND "${CMAKE_COMMAND}" -E touch "${_stamp}"
    DEPENDS "${_file}"
    COMMENT "Validating NoDL ${kind} definition ${_name}"
    VERBATIM)
  add_custom_target(ament_nodl_validate_${resource_type}_${_target_key} ALL DEPENDS "${_stamp}")

  install(FILES "${_file}" DESTINATION "share/${PROJECT_NAME}/nodl")
  ament_index_register_resource(${resource_type}
    PACKAGE_NAME "${PROJECT_NAME}__${key}"
    CONTENT "nodl/${_name}")
endfunction()
