# Installs the step folders (CMakeLists.txt's install(SCRIPT)): labs/ (PBRLAB_SOURCE_LABS), or
# the folders in $PBRLAB_INSTALL_STEPS, read when `cmake --install` or `cpack` runs, so that one
# build makes both packages. Those are an assignment's student package: the folders
# `pbrlab kit --assignment A --date D --site-steps` writes, with no solution the assignment has
# not released on that date and no step after the last one released
# (scripts/package-assignment.sh). The plugins of the steps left out are removed too: they
# would only warn that no folder declares them.
set(steps "$ENV{PBRLAB_INSTALL_STEPS}")
if(NOT steps)
  set(steps "${PBRLAB_SOURCE_LABS}")
elseif(NOT EXISTS "${steps}")
  message(FATAL_ERROR "PBRLAB_INSTALL_STEPS=${steps}: no such folder")
endif()
file(INSTALL "${steps}/" DESTINATION "${CMAKE_INSTALL_PREFIX}/share/pbrlab/labs"
     PATTERN CMakeLists.txt EXCLUDE)
if(DEFINED ENV{PBRLAB_INSTALL_STEPS})
  file(GLOB modules "$ENV{DESTDIR}${CMAKE_INSTALL_PREFIX}/lib/pbrlab/modules/pbrlab-*.so")
  foreach(module IN LISTS modules)
    get_filename_component(name "${module}" NAME_WE)
    string(REGEX REPLACE "^pbrlab-" "" id "${name}")
    if(NOT EXISTS "${steps}/${id}/step.json")
      message(STATUS "Left out (no step folder): ${module}")
      file(REMOVE "${module}")
    endif()
  endforeach()
endif()
