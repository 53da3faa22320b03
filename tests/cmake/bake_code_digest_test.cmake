# Runs cmake/BakeCodeDigest.cmake on a small tree of its own and checks what changes the digest: a file's content, a
# file's path, the build line and the set of files do; touching a file without changing it does not, and an unchanged
# digest leaves the generated source as it was. Run as: cmake -DSOURCE_DIR=<repository> -DWORK_DIR=<scratch> -P ...
set(root ${WORK_DIR}/tree)
set(out ${WORK_DIR}/digest.cpp)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${root}/engine)
file(WRITE ${root}/engine/a.cpp "int a() { return 1; }\n")
file(WRITE ${root}/engine/b.hpp "int a();\n")

# The digest of the tree for `files` (relative paths) and `build`, in `var`.
function(digest_of var files build)
  string(REPLACE ";" "\n" lines "${files}")
  file(WRITE ${WORK_DIR}/list.txt "${lines}\n")
  execute_process(COMMAND ${CMAKE_COMMAND} -DROOT=${root} -DLIST=${WORK_DIR}/list.txt -DBUILD=${build} -DOUT=${out}
                          -P ${SOURCE_DIR}/cmake/BakeCodeDigest.cmake RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "BakeCodeDigest.cmake failed (${rc}): ${err}")
  endif()
  file(READ ${out} text)
  if(NOT text MATCHES "kBakeCodeDigest\\[\\] = \"([0-9a-f]+)\";")
    message(FATAL_ERROR "no digest in ${out}:\n${text}")
  endif()
  string(LENGTH "${CMAKE_MATCH_1}" n)
  if(NOT n EQUAL 64)
    message(FATAL_ERROR "the digest has ${n} hexadecimal digits, not 64: ${CMAKE_MATCH_1}")
  endif()
  set(${var} ${CMAKE_MATCH_1} PARENT_SCOPE)
endfunction()

function(expect what a op b)
  if(op STREQUAL "same" AND NOT a STREQUAL b)
    message(FATAL_ERROR "${what}: the digest changed (${a} -> ${b})")
  elseif(op STREQUAL "differs" AND a STREQUAL b)
    message(FATAL_ERROR "${what}: the digest did not change (${a})")
  endif()
  message(STATUS "${what}: ${op}")
endfunction()

set(files engine/a.cpp engine/b.hpp)
digest_of(first "${files}" "GNU 12|-O2")
file(TIMESTAMP ${out} written_at "%s")
execute_process(COMMAND ${CMAKE_COMMAND} -E sleep 1.1)
file(TOUCH ${root}/engine/a.cpp)
digest_of(touched "${files}" "GNU 12|-O2")
expect("a file touched, not changed" ${first} same ${touched})
file(TIMESTAMP ${out} rewritten_at "%s")
if(NOT written_at STREQUAL rewritten_at)
  message(FATAL_ERROR "the generated source was rewritten with the same digest (${written_at} -> ${rewritten_at})")
endif()
if(NOT EXISTS ${out}.stamp)
  message(FATAL_ERROR "no ${out}.stamp")
endif()

file(WRITE ${root}/engine/a.cpp "int a() { return 2; }\n")
digest_of(edited "${files}" "GNU 12|-O2")
expect("a file's content edited" ${first} differs ${edited})

digest_of(flags "${files}" "GNU 12|-O3")
expect("other flags" ${edited} differs ${flags})

file(RENAME ${root}/engine/b.hpp ${root}/engine/c.hpp)
digest_of(renamed "engine/a.cpp;engine/c.hpp" "GNU 12|-O2")
expect("a file renamed" ${edited} differs ${renamed})

digest_of(fewer "engine/a.cpp" "GNU 12|-O2")
expect("a file fewer" ${renamed} differs ${fewer})

file(WRITE ${root}/engine/c.hpp "int a();\n")  # back to the first contents and paths
file(RENAME ${root}/engine/c.hpp ${root}/engine/b.hpp)
file(WRITE ${root}/engine/a.cpp "int a() { return 1; }\n")
digest_of(again "${files}" "GNU 12|-O2")
expect("the same files and build again" ${first} same ${again})

# A listed file that is gone fails the step (the build stops until CMake lists the files again).
file(WRITE ${WORK_DIR}/list.txt "engine/a.cpp\nengine/gone.cpp\n")
execute_process(COMMAND ${CMAKE_COMMAND} -DROOT=${root} -DLIST=${WORK_DIR}/list.txt -DBUILD=x -DOUT=${out}
                        -P ${SOURCE_DIR}/cmake/BakeCodeDigest.cmake RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
if(rc EQUAL 0)
  message(FATAL_ERROR "a missing listed file did not fail the digest step")
endif()
message(STATUS "a missing listed file fails the step")
file(REMOVE_RECURSE ${WORK_DIR})
