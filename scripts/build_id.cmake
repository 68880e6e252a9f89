# Writes OUTPUT, a C++ file defining igi::build_id(), at every build (the
# igi_build_id target runs it): "igi-cluster DESCRIBE DETAILS", DESCRIBE being
# `git describe --always --dirty --abbrev=12` of SOURCE_DIR ("unknown" outside
# git). OUTPUT is rewritten only when its text changes, so an unchanged tree
# recompiles nothing and a new commit or an edit recompiles this one file.
#   cmake -DSOURCE_DIR=... -DOUTPUT=... -DDETAILS="GNU-12.2.0 embree-3.13.5 isa=avx2" -P build_id.cmake
execute_process(COMMAND git describe --always --dirty --abbrev=12 WORKING_DIRECTORY ${SOURCE_DIR}
                OUTPUT_VARIABLE describe OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE failed)
if(failed OR NOT describe)
  set(describe "unknown")
endif()
set(text "// Generated at build time by scripts/build_id.cmake from `git describe`: do not edit.
#include \"build_id.h\"

const char* igi::build_id() { return \"igi-cluster ${describe} ${DETAILS}\"; }
")
set(old "")
if(EXISTS ${OUTPUT})
  file(READ ${OUTPUT} old)
endif()
if(NOT old STREQUAL text)
  file(WRITE ${OUTPUT} "${text}")
endif()
