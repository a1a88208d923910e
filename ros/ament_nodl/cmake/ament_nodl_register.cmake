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
# :param PLUGIN: optional, the composable node class (pkg::ClassName) the definition
#   describes, so that `nodl analyse` matches ComposableNode(plugin=...) to it
# :param NODE_NAME: optional, the name the executable gives its node when launched
#   without one (NoDL keeps identity out of the definition)
# Both are recorded in the ament index as nodl_node_info/<package>__<executable>.
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
  if(kind STREQUAL "node")
    set(_one FILE PLUGIN NODE_NAME)
    set(_usage "<key> FILE <file> [PLUGIN <pkg::ClassName>] [NODE_NAME <name>]")
  else()
    set(_one FILE)
    set(_usage "<key> FILE <file>")
  endif()
  cmake_parse_arguments(ARG "" "${_one}" "" ${ARGN})
  if(ARG_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "${_what}: unexpected arguments '${ARG_UNPARSED_ARGUMENTS}'; "
      "usage: ament_nodl_register_${kind}(${_usage})")
  endif()
  set(_info "")
  if(ARG_PLUGIN)
    if(NOT ARG_PLUGIN MATCHES "^[A-Za-z_][A-Za-z0-9_]*(::[A-Za-z_][A-Za-z0-9_]*)*$")
      message(FATAL_ERROR "${_what}: PLUGIN '${ARG_PLUGIN}' is not a class name (pkg::ClassName)")
    endif()
    string(APPEND _info "plugin=${ARG_PLUGIN}\n")
  endif()
  if(ARG_NODE_NAME)
    if(NOT ARG_NODE_NAME MATCHES "^[A-Za-z_][A-Za-z0-9_]*$")
      message(FATAL_ERROR "${_what}: NODE_NAME '${ARG_NODE_NAME}' is not a valid node name")
    endif()
    string(APPEND _info "node_name=${ARG_NODE_NAME}\n")
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
  _ament_nodl_claim("${_what}" "nodl/${_name}" "${_file}" _claimed)

  # A staging index in the build folder lets build-time validation resolve
  # nodl://<this package>/<name> before the package is installed.
  set(_stage "${CMAKE_BINARY_DIR}/ament_nodl_stage")
  # Rebuilt at every configure: an entry left over from an earlier configure (a
  # registration since removed) would let a reference to it pass validation here and
  # fail once the package is installed.
  get_property(_stage_cleared GLOBAL PROPERTY _AMENT_NODL_STAGE_CLEARED)
  if(NOT _stage_cleared)
    set_property(GLOBAL PROPERTY _AMENT_NODL_STAGE_CLEARED TRUE)
    file(REMOVE_RECURSE "${_stage}")
  endif()
  file(WRITE "${_stage}/share/ament_index/resource_index/packages/${PROJECT_NAME}" "")
  file(WRITE "${_stage}/share/ament_index/resource_index/${resource_type}/${PROJECT_NAME}__${key}"
    "${_file}")
  # Validation runs once per package, after the whole CMakeLists has been read, so
  # that every invalid file is reported (a build step per file would stop at the
  # first failure) and nodl://<this package>/<name> references resolve whatever
  # the order of the registrations.
  set_property(GLOBAL APPEND PROPERTY _AMENT_NODL_VALIDATE "${kind}|${_file}")
  if(CMAKE_VERSION VERSION_LESS 3.19)
    # No deferred calls: one step per file.
    string(MAKE_C_IDENTIFIER "${resource_type}_${key}" _target_key)
    _ament_nodl_add_validation("${_target_key}" "${kind}|${_file}")
  else()
    get_property(_scheduled GLOBAL PROPERTY _AMENT_NODL_SCHEDULED)
    if(NOT _scheduled)
      set_property(GLOBAL PROPERTY _AMENT_NODL_SCHEDULED TRUE)
      cmake_language(DEFER DIRECTORY "${CMAKE_SOURCE_DIR}" CALL _ament_nodl_add_deferred_validation)
    endif()
  endif()

  install(FILES "${_file}" DESTINATION "share/${PROJECT_NAME}/nodl")
  if(kind STREQUAL "node")
    _ament_nodl_install_relative_mixins("${_what}" "${_file}")
  endif()
  ament_index_register_resource(${resource_type}
    PACKAGE_NAME "${PROJECT_NAME}__${key}"
    CONTENT "nodl/${_name}")
  if(NOT _info STREQUAL "")
    # read back by nodl.registry.node_info
    ament_index_register_resource(nodl_node_info
      PACKAGE_NAME "${PROJECT_NAME}__${key}"
      CONTENT "${_info}")
  endif()
endfunction()

# Record that <file> is installed as share/<package>/<target>; fail if another file
# already is. <claimed_var> is set to TRUE when <file> was already recorded there.
function(_ament_nodl_claim what target file claimed_var)
  set(${claimed_var} FALSE PARENT_SCOPE)
  get_property(_installed GLOBAL PROPERTY _AMENT_NODL_INSTALLED)
  foreach(_entry IN LISTS _installed)
    string(REPLACE "|" ";" _pair "${_entry}")
    list(GET _pair 0 _other_target)
    list(GET _pair 1 _other_file)
    if(_other_target STREQUAL target)
      if(NOT _other_file STREQUAL file)
        message(FATAL_ERROR "${what}: '${file}' and '${_other_file}' would both be installed "
          "as share/${PROJECT_NAME}/${target}; rename one")
      endif()
      set(${claimed_var} TRUE PARENT_SCOPE)
      return()
    endif()
  endforeach()
  set_property(GLOBAL APPEND PROPERTY _AMENT_NODL_INSTALLED "${target}|${file}")
endfunction()

# Install the mixins of a node file that are files of this package (relative paths) at
# the same place relative to the installed node file, so that the installed copy
# resolves them as the build-time validation did. `nodl deps` lists them.
function(_ament_nodl_install_relative_mixins what file)
  # The file's mixins decide what is installed: reconfigure when it changes.
  set_property(DIRECTORY "${CMAKE_CURRENT_SOURCE_DIR}" APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
    "${file}")
  execute_process(COMMAND "${AMENT_NODL_EXECUTABLE}" deps "${file}"
    OUTPUT_VARIABLE _out ERROR_VARIABLE _err RESULT_VARIABLE _rc)
  if(_rc EQUAL 1)
    # Not a valid definition: its mixins cannot be known, and the build's validation step
    # fails the package with every problem at its FILE:LINE:COL.
    return()
  elseif(NOT _rc EQUAL 0)
    message(FATAL_ERROR "${what}: '${AMENT_NODL_EXECUTABLE} deps ${file}' failed (${_rc}): ${_err}")
  endif()
  get_filename_component(_dir "${file}" DIRECTORY)
  string(REPLACE "\n" ";" _references "${_out}")
  foreach(_reference IN LISTS _references)
    if(_reference STREQUAL "")
      continue()
    endif()
    # The node file is installed in share/<package>/nodl: its mixin goes to nodl/<reference>.
    if(_reference MATCHES "^\\.\\./\\.\\.(/|$)")
      message(FATAL_ERROR "${what}: mixin '${_reference}' of '${file}' would be installed outside "
        "share/${PROJECT_NAME}; keep relative mixins in or below the folder above the node "
        "file, or register the mixin as an interface and use nodl://${PROJECT_NAME}/<name>")
    elseif(_reference MATCHES "^\\.\\./(.*)$")
      set(_target "${CMAKE_MATCH_1}")
    else()
      set(_target "nodl/${_reference}")
    endif()
    get_filename_component(_source "${_reference}" ABSOLUTE BASE_DIR "${_dir}")
    if(NOT EXISTS "${_source}")
      continue()  # the build-time validation reports it, with its position
    endif()
    _ament_nodl_claim("${what}" "${_target}" "${_source}" _claimed)
    if(NOT _claimed)
      get_filename_component(_target_dir "${_target}" DIRECTORY)
      install(FILES "${_source}" DESTINATION "share/${PROJECT_NAME}/${_target_dir}")
    endif()
  endforeach()
endfunction()

function(_ament_nodl_add_deferred_validation)
  get_property(_entries GLOBAL PROPERTY _AMENT_NODL_VALIDATE)
  _ament_nodl_add_validation(all ${_entries})
endfunction()

# A build step that validates every <kind>|<file> entry (kind enforced, mixin references
# resolved against the staging index and AMENT_PREFIX_PATH) and fails if any is invalid.
function(_ament_nodl_add_validation suffix)
  if(WIN32)
    set(_sep ";")
  else()
    set(_sep ":")
  endif()
  set(_prefixes "${CMAKE_BINARY_DIR}/ament_nodl_stage")
  if(NOT "$ENV{AMENT_PREFIX_PATH}" STREQUAL "")
    set(_prefixes "${_prefixes}${_sep}$ENV{AMENT_PREFIX_PATH}")
  endif()
  # The endpoint types are checked against the installed interfaces and this package's
  # package.xml (an interface package declared but not installed is only a warning here:
  # build farms install no exec-only dependency for a build). Turn it off with
  # set(AMENT_NODL_CHECK_TYPES OFF) before the registrations, or -DAMENT_NODL_CHECK_TYPES=OFF.
  set(_types "")
  if(NOT DEFINED AMENT_NODL_CHECK_TYPES OR AMENT_NODL_CHECK_TYPES)
    set(_types "--types-at-build --package [==[${PROJECT_SOURCE_DIR}]==] ")
  endif()
  set(_dir "${CMAKE_BINARY_DIR}/ament_nodl")
  set(_script "${_dir}/validate_${suffix}.cmake")
  set(_content "# Generated by ament_nodl: validates the NoDL definitions of ${PROJECT_NAME}.\n")
  string(APPEND _content "set(ENV{AMENT_PREFIX_PATH} [==[${_prefixes}]==])\n")
  string(APPEND _content "set(_failed \"\")\n")
  set(_files "")
  foreach(_entry IN LISTS ARGN)
    string(REPLACE "|" ";" _pair "${_entry}")
    list(GET _pair 0 _kind)
    list(GET _pair 1 _file)
    list(APPEND _files "${_file}")
    # A node is composed with the base of the client library an ament_cmake package's
    # nodes get everywhere else (nodl analyse, show, check: the build type's, rclcpp).
    set(_library "")
    if(_kind STREQUAL "node")
      set(_library "--client-library rclcpp ")
    endif()
    string(APPEND _content
      "execute_process(COMMAND [==[${AMENT_NODL_EXECUTABLE}]==] validate --kind ${_kind} "
      "--resolve ${_library}${_types}--quiet --stderr [==[${_file}]==] RESULT_VARIABLE _rc)\n"
      "if(NOT _rc EQUAL 0)\n  list(APPEND _failed [==[${_file}]==])\nendif()\n")
  endforeach()
  string(APPEND _content
    "if(_failed)\n"
    "  string(REPLACE \";\" \", \" _failed \"\${_failed}\")\n"
    "  message(FATAL_ERROR \"${PROJECT_NAME}: invalid NoDL definitions: \${_failed}\")\n"
    "endif()\n")
  # Rewritten only when it changes, so that reconfiguring does not revalidate.
  file(WRITE "${_script}.in" "${_content}")
  configure_file("${_script}.in" "${_script}" COPYONLY)

  set(_stamp "${_dir}/validate_${suffix}.valid")
  add_custom_command(
    OUTPUT "${_stamp}"
    COMMAND "${CMAKE_COMMAND}" -P "${_script}"
    COMMAND "${CMAKE_COMMAND}" -E touch "${_stamp}"
    DEPENDS ${_files} "${_script}"
    COMMENT "Validating the NoDL definitions of ${PROJECT_NAME}"
    VERBATIM)
  add_custom_target(ament_nodl_validate_${suffix} ALL DEPENDS "${_stamp}")
endfunction()
