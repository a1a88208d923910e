# Code generation from NoDL node definitions at build time.
#
#   ament_nodl_generate_cpp(<target> <definition>
#     [CLASS_NAME <Name>] [NODE_NAME <name>] [NAMESPACE <ns>] [COMPONENT])
#   ament_nodl_generate_python(<definition> [MODULE <name>] [CLASS_NAME <Name>] [NODE_NAME <name>]
#     [DESTINATION <python package folder>])
#
# Both run `nodl generate` (the command ament_nodl found) and regenerate when the definition
# or a file it composes (its relative mixins, as `nodl deps` lists them) changes.

#
# Generate the rclcpp base class of a node and build it as the library <target>.
#
# The library holds <stem>_base.cpp (stem from the class name), exports the folder of
# <stem>_base.hpp as a PUBLIC include directory and links what the generated code needs:
# rclcpp, rclcpp_lifecycle for a lifecycle node, rclcpp_action for actions,
# rclcpp_components with COMPONENT, and every interface package it uses (the header's
# `// nodl-dependencies:` line). Link your executable or component to <target>.
#
# :param target: the library target to create
# :param definition: the node definition, relative to CMAKE_CURRENT_SOURCE_DIR
# :param CLASS_NAME: the class stem (<Name>Base); default from the file name
# :param NODE_NAME: the constructor's default node name; default from the file name
# :param NAMESPACE: the C++ namespace; default the node name
# :param COMPONENT: include rclcpp_components' registration macro (and link it)
#
function(ament_nodl_generate_cpp target definition)
  set(_what "ament_nodl_generate_cpp(${target})")
  cmake_parse_arguments(ARG "COMPONENT" "CLASS_NAME;NODE_NAME;NAMESPACE" "" ${ARGN})
  if(ARG_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "${_what}: unexpected arguments '${ARG_UNPARSED_ARGUMENTS}'; usage: "
      "ament_nodl_generate_cpp(<target> <definition> [CLASS_NAME <Name>] [NODE_NAME <name>] "
      "[NAMESPACE <ns>] [COMPONENT])")
  endif()
  if(TARGET ${target})
    message(FATAL_ERROR "${_what}: a target named '${target}' already exists")
  endif()
  set(_options "")
  foreach(_option CLASS_NAME NODE_NAME NAMESPACE)
    if(ARG_${_option})
      string(TOLOWER "${_option}" _flag)
      string(REPLACE "_" "-" _flag "${_flag}")
      list(APPEND _options "--${_flag}" "${ARG_${_option}}")
    endif()
  endforeach()
  if(ARG_COMPONENT)
    list(APPEND _options --component)
  endif()
  set(_out "${CMAKE_CURRENT_BINARY_DIR}/ament_nodl_generate_cpp/${target}")
  _ament_nodl_generate_files("${_what}" cpp "${definition}" "${_out}" "${_options}"
    _definition _files _depends)

  set(_sources "")
  set(_header "")
  foreach(_file IN LISTS _files)
    if(_file MATCHES "\\.cpp$")
      list(APPEND _sources "${_out}/${_file}")
    elseif(_file MATCHES "\\.hpp$")
      set(_header "${_out}/${_file}")
    endif()
  endforeach()
  if(NOT _sources OR NOT _header)
    message(FATAL_ERROR "${_what}: 'nodl generate --language cpp' wrote no header and source")
  endif()
  # The packages the generated code needs, as its header names them.
  file(STRINGS "${_header}" _line REGEX "^// nodl-dependencies:" LIMIT_COUNT 1)
  string(REGEX REPLACE "^// nodl-dependencies: *" "" _line "${_line}")
  string(REPLACE " " ";" _dependencies "${_line}")

  add_library(${target} "${_sources}")
  target_include_directories(${target} PUBLIC
    "$<BUILD_INTERFACE:${_out}>" "$<INSTALL_INTERFACE:include/${PROJECT_NAME}>")
  target_compile_features(${target} PUBLIC cxx_std_17)
  foreach(_dependency IN LISTS _dependencies)
    if(NOT _dependency)
      continue()
    endif()
    find_package(${_dependency} REQUIRED)
    # An interface package: its C++ headers and C++ type support (not its other languages').
    set(_cpp "${_dependency}::${_dependency}__rosidl_generator_cpp")
    set(_typesupport "${_dependency}::${_dependency}__rosidl_typesupport_cpp")
    if(TARGET ${_cpp} AND TARGET ${_typesupport})
      target_link_libraries(${target} PUBLIC ${_cpp} ${_typesupport})
    elseif(DEFINED ${_dependency}_TARGETS)
      target_link_libraries(${target} PUBLIC ${${_dependency}_TARGETS})
    elseif(_dependency STREQUAL "rclcpp_components" AND TARGET rclcpp_components::component)
      target_link_libraries(${target} PUBLIC rclcpp_components::component)
    elseif(TARGET ${_dependency}::${_dependency})
      target_link_libraries(${target} PUBLIC ${_dependency}::${_dependency})
    else()
      message(FATAL_ERROR "${_what}: package '${_dependency}' has no target to link to "
        "(${_dependency}::${_dependency} or \${${_dependency}_TARGETS})")
    endif()
  endforeach()
  set_property(TARGET ${target} PROPERTY AMENT_NODL_DEPENDENCIES "${_dependencies}")
  set_property(TARGET ${target} PROPERTY AMENT_NODL_DEFINITION "${_definition}")
endfunction()

#
# Generate the rclpy base class of a node as a module of an ament_cmake_python package.
#
# The module is generated into the build folder and installed into the Python package
# folder DESTINATION (default: ${PROJECT_NAME}, as ament_python_install_package installs it)
# under PYTHON_INSTALL_DIR.
#
# :param definition: the node definition, relative to CMAKE_CURRENT_SOURCE_DIR
# :param CLASS_NAME: the class stem (<Name>Base); default from the file name
# :param NODE_NAME: the constructor's default node name; default from the file name
# :param DESTINATION: the Python package the module goes into
#
function(ament_nodl_generate_python definition)
  set(_what "ament_nodl_generate_python(${definition})")
  cmake_parse_arguments(ARG "" "CLASS_NAME;NODE_NAME;DESTINATION" "" ${ARGN})
  if(ARG_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "${_what}: unexpected arguments '${ARG_UNPARSED_ARGUMENTS}'; usage: "
      "ament_nodl_generate_python(<definition> [CLASS_NAME <Name>] [NODE_NAME <name>] "
      "[DESTINATION <package>])")
  endif()
  set(_options "")
  foreach(_option CLASS_NAME NODE_NAME)
    if(ARG_${_option})
      string(TOLOWER "${_option}" _flag)
      string(REPLACE "_" "-" _flag "${_flag}")
      list(APPEND _options "--${_flag}" "${ARG_${_option}}")
    endif()
  endforeach()
  if(NOT ARG_DESTINATION)
    set(ARG_DESTINATION "${PROJECT_NAME}")
  endif()
  string(MAKE_C_IDENTIFIER "${definition}" _key)
  set(_out "${CMAKE_CURRENT_BINARY_DIR}/ament_nodl_generate_python/${_key}")
  _ament_nodl_generate_files("${_what}" python "${definition}" "${_out}" "${_options}"
    _definition _files _depends)
  set(_outputs "")
  foreach(_file IN LISTS _files)
    list(APPEND _outputs "${_out}/${_file}")
  endforeach()
  add_custom_target(ament_nodl_generate_python_${_key} ALL DEPENDS ${_outputs})
  if(NOT PYTHON_INSTALL_DIR)
    find_package(ament_cmake_python REQUIRED)
    _ament_cmake_python_get_python_install_dir()
  endif()
  install(FILES ${_outputs} DESTINATION "${PYTHON_INSTALL_DIR}/${ARG_DESTINATION}")
endfunction()

# Generate <language> files from <definition> into <out>: once at configure time (to learn
# the file names), and by a build step that reruns when the definition or one of its
# relative mixins changes. Sets <definition_var> (absolute), <files_var> (names in <out>)
# and <depends_var> (the files the step depends on).
function(_ament_nodl_generate_files what language definition out options
    definition_var files_var depends_var)
  get_filename_component(_definition "${definition}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
  if(NOT EXISTS "${_definition}")
    message(FATAL_ERROR "${what}: file '${_definition}' does not exist")
  endif()
  set(_command "${AMENT_NODL_EXECUTABLE}" generate "${_definition}" --language ${language}
    ${options})

  # The names of the files, from a generation into an empty folder.
  set(_probe "${out}.configure")
  file(REMOVE_RECURSE "${_probe}")
  execute_process(COMMAND ${_command} -o "${_probe}"
    OUTPUT_QUIET ERROR_VARIABLE _err RESULT_VARIABLE _rc)
  if(NOT _rc EQUAL 0)
    message(FATAL_ERROR "${what}: 'nodl generate --language ${language} ${_definition}' "
      "failed:\n${_err}")
  endif()
  file(GLOB_RECURSE _files RELATIVE "${_probe}" "${_probe}/*")
  list(SORT _files)
  # Sources must exist when the target is defined; later builds regenerate them.
  foreach(_file IN LISTS _files)
    configure_file("${_probe}/${_file}" "${out}/${_file}" COPYONLY)
  endforeach()
  file(REMOVE_RECURSE "${_probe}")

  # The definition and its relative mixins: the build step depends on them, and a change
  # reconfigures (the mixins, the file names or the dependencies may change with it).
  execute_process(COMMAND "${AMENT_NODL_EXECUTABLE}" deps "${_definition}"
    OUTPUT_VARIABLE _deps_out ERROR_VARIABLE _err RESULT_VARIABLE _rc)
  if(NOT _rc EQUAL 0)
    message(FATAL_ERROR "${what}: 'nodl deps ${_definition}' failed: ${_err}")
  endif()
  get_filename_component(_dir "${_definition}" DIRECTORY)
  set(_depends "${_definition}")
  string(REPLACE "\n" ";" _references "${_deps_out}")
  foreach(_reference IN LISTS _references)
    if(NOT _reference STREQUAL "")
      get_filename_component(_path "${_reference}" ABSOLUTE BASE_DIR "${_dir}")
      list(APPEND _depends "${_path}")
    endif()
  endforeach()
  set_property(DIRECTORY "${CMAKE_CURRENT_SOURCE_DIR}" APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
    ${_depends})

  set(_outputs "")
  foreach(_file IN LISTS _files)
    list(APPEND _outputs "${out}/${_file}")
  endforeach()
  add_custom_command(
    OUTPUT ${_outputs}
    COMMAND ${_command} -o "${out}"
    # unchanged files keep their time stamp; touch them so the step is done
    COMMAND "${CMAKE_COMMAND}" -E touch_nocreate ${_outputs}
    DEPENDS ${_depends}
    COMMENT "Generating ${language} from NoDL definition ${definition}"
    VERBATIM)

  set(${definition_var} "${_definition}" PARENT_SCOPE)
  set(${files_var} "${_files}" PARENT_SCOPE)
  set(${depends_var} "${_depends}" PARENT_SCOPE)
endfunction()
