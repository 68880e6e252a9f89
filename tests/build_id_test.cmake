# scripts/build_id.cmake in a scratch git repository: the id follows the tree
# (a commit, an edit: -dirty), and an unchanged tree leaves the generated file
# untouched, so a rebuild compiles nothing.
#   cmake -DSCRIPT=scripts/build_id.cmake -DWORK_DIR=... -P build_id_test.cmake
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR}/tree)
set(out ${WORK_DIR}/build_id.cpp)

function(git)
  execute_process(COMMAND git -c user.name=test -c user.email=test@example.invalid ${ARGN}
                  WORKING_DIRECTORY ${WORK_DIR}/tree RESULT_VARIABLE failed OUTPUT_QUIET ERROR_QUIET)
  if(failed)
    message(FATAL_ERROR "git ${ARGN} failed")
  endif()
endfunction()

function(generate)
  execute_process(COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${WORK_DIR}/tree -DOUTPUT=${out} "-DDETAILS=GNU-1 isa=x"
                          -P ${SCRIPT} RESULT_VARIABLE failed)
  if(failed)
    message(FATAL_ERROR "build_id.cmake failed")
  endif()
endfunction()

function(expect_id expected)
  file(READ ${out} text)
  string(FIND "${text}" "\"igi-cluster ${expected} GNU-1 isa=x\"" at)
  if(at LESS 0)
    message(FATAL_ERROR "expected the id 'igi-cluster ${expected} GNU-1 isa=x' in:\n${text}")
  endif()
endfunction()

function(head_commit result)
  execute_process(COMMAND git rev-parse --short=12 HEAD WORKING_DIRECTORY ${WORK_DIR}/tree
                  OUTPUT_VARIABLE commit OUTPUT_STRIP_TRAILING_WHITESPACE)
  set(${result} ${commit} PARENT_SCOPE)
endfunction()

git(init -q)
file(WRITE ${WORK_DIR}/tree/source.cpp "int a;\n")
git(add source.cpp)
git(commit -q -m first)
head_commit(first)
generate()
expect_id(${first})

# Unchanged tree: the file keeps its modification time (a second apart would show).
file(TIMESTAMP ${out} before "%s")
execute_process(COMMAND ${CMAKE_COMMAND} -E sleep 1.1)
generate()
file(TIMESTAMP ${out} after "%s")
if(NOT before STREQUAL after)
  message(FATAL_ERROR "an unchanged tree rewrote ${out} (${before} -> ${after})")
endif()

# An edit, then a commit: each is a new id, without configuring anything.
file(WRITE ${WORK_DIR}/tree/source.cpp "int b;\n")
generate()
expect_id(${first}-dirty)
git(commit -q -a -m second)
head_commit(second)
generate()
expect_id(${second})
message(STATUS "build id follows the tree: ${first}, ${first}-dirty, ${second}")
