# The portable layers build alone (core/README.md): a configure with -DPBRLAB_PORTABLE_ONLY=ON
# that looks for none of the native libraries (OpenImageIO, GLFW, Dear ImGui, CLI11; OSMesa is
# only ever opened at run time) and builds pbrlab_portable, every portable layer's objects.
# Usage: cmake -DSOURCE=<repository> -DBINARY=<build folder> -DGENERATOR=<name> -P build_portable.cmake
foreach(step configure build)
  if(step STREQUAL configure)
    set(command ${CMAKE_COMMAND} -S ${SOURCE} -B ${BINARY} -G ${GENERATOR}
                -DPBRLAB_PORTABLE_ONLY=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo)
  else()
    cmake_host_system_information(RESULT cores QUERY NUMBER_OF_LOGICAL_CORES)
    set(command ${CMAKE_COMMAND} --build ${BINARY} --target pbrlab_portable -j ${cores})
  endif()
  execute_process(COMMAND ${command} RESULT_VARIABLE result OUTPUT_VARIABLE out
                  ERROR_VARIABLE out)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "the portable build failed at its ${step}:\n${out}")
  endif()
  # The project builds with zero warnings (-Wall -Wextra); a scratch build here shows them all.
  if(out MATCHES "warning:")
    message(FATAL_ERROR "the portable build warns at its ${step}:\n${out}")
  endif()
endforeach()
# What the configure looked for: none of the native platform's libraries.
file(STRINGS ${BINARY}/CMakeCache.txt looked REGEX "^(OIIO|IMGUI|glfw3|CLI11|OPENGL)[A-Za-z_]*:")
if(looked)
  list(JOIN looked "\n  " looked)
  message(FATAL_ERROR "the portable configure looked for native libraries:\n  ${looked}")
endif()
if(NOT EXISTS ${BINARY}/core/libpbrlab_portable.a)
  message(FATAL_ERROR "the portable build made no ${BINARY}/core/libpbrlab_portable.a")
endif()
message(STATUS "pbrlab_portable built without the native libraries")
