# check_layers.cmake can fail: on tests/layers/broken (a lower layer including a higher one,
# a portable layer using fork and <sys/wait.h>, two layers allowed to include each other, a
# folder with no README, a file outside any layer) it fails and names each problem, and it
# names nothing that is allowed (the higher layer including the lower one and calling fork).
# Usage: cmake -DCHECK=<check_layers.cmake> -DBROKEN=<the broken tree> -P expect_problems.cmake
execute_process(COMMAND ${CMAKE_COMMAND} -DCORE=${BROKEN} -P ${CHECK}
                RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
set(out "${out}${err}")
if(result EQUAL 0)
  message(FATAL_ERROR "check_layers passed a tree with six problems:\n${out}")
endif()
foreach(expected
    "core/low/wrong_way.cpp: '#include \"high/fine.h\"': layer low includes layer high"
    "core/low/wrong_way.cpp: '#include <sys/wait.h>': layer low is portable"
    "core/low/wrong_way.cpp: calls fork\\(\\): layer low is portable"
    "the 'May include' lines of loop_a, loop_b make a cycle"
    "core/no_readme: no README.md"
    "core/loose.h: a source file outside any layer folder"
    "check_layers: 6 problem\\(s\\)")
  if(NOT out MATCHES "${expected}")
    message(FATAL_ERROR "check_layers did not report '${expected}':\n${out}")
  endif()
endforeach()
if(out MATCHES "core/high/")
  message(FATAL_ERROR "check_layers reported an allowed include of core/high:\n${out}")
endif()
message(STATUS "check_layers reports each of the broken tree's problems")
