# pbrlab_add_step(<step folder> [API <target>] [OUTPUT_DIRECTORY <dir>] [TARGET_OUT <var>]
#                 [NO_LINK])
#
# Builds a step folder's module.cpp into <dir>/pbrlab-<id>.so, <id> read from the folder's
# step.json, and, for a folder outside <dir>, links <dir>/<id> to the folder, so that
# `pbrlab --modules <dir>` finds both the library and the step's GLSL, handout and step.json.
# API: the target the module compiles against (pbrlab::module_api from the installed package).
# OUTPUT_DIRECTORY: default ${CMAKE_BINARY_DIR}/modules. TARGET_OUT: receives the target name.
# NO_LINK: the host finds the folder another way (the built-in steps, in labs/).
function(pbrlab_add_step folder)
  cmake_parse_arguments(ARG "NO_LINK" "API;OUTPUT_DIRECTORY;TARGET_OUT" "" ${ARGN})
  if(NOT ARG_API)
    set(ARG_API pbrlab::module_api)
  endif()
  if(NOT ARG_OUTPUT_DIRECTORY)
    set(ARG_OUTPUT_DIRECTORY "${CMAKE_BINARY_DIR}/modules")
  endif()
  get_filename_component(folder "${folder}" ABSOLUTE)
  if(NOT EXISTS "${folder}/step.json")
    message(FATAL_ERROR "pbrlab_add_step: ${folder}/step.json does not exist")
  endif()
  file(READ "${folder}/step.json" step_json)
  string(JSON id ERROR_VARIABLE json_error GET "${step_json}" id)
  if(json_error)
    message(FATAL_ERROR "pbrlab_add_step: ${folder}/step.json: no \"id\" (${json_error})")
  endif()
  # The step.json is read again when it changes (its id names the library).
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${folder}/step.json")
  set(target pbrlab-${id})
  add_library(${target} MODULE "${folder}/module.cpp")
  set_target_properties(${target} PROPERTIES
    PREFIX ""
    LIBRARY_OUTPUT_DIRECTORY "${ARG_OUTPUT_DIRECTORY}")
  target_link_libraries(${target} PRIVATE ${ARG_API})
  if(NOT ARG_NO_LINK)
    file(MAKE_DIRECTORY "${ARG_OUTPUT_DIRECTORY}")
    file(CREATE_LINK "${folder}" "${ARG_OUTPUT_DIRECTORY}/${id}" SYMBOLIC)
  endif()
  if(ARG_TARGET_OUT)
    set(${ARG_TARGET_OUT} ${target} PARENT_SCOPE)
  endif()
endfunction()
