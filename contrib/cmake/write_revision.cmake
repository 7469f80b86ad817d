# Writes ${OUTPUT}: a header with the git revision of ${SOURCE_DIR} (or
# "unknown" outside a git checkout), rewritten only when the revision
# changes so that main.cc is recompiled only then. Run at every build by
# the talus_revision target, so that `talus --version` names the commit the
# executable was built from, not the one cmake was last run at.
execute_process(
  COMMAND git -C ${SOURCE_DIR} describe --always --dirty --abbrev=12
  OUTPUT_VARIABLE _revision
  OUTPUT_STRIP_TRAILING_WHITESPACE
  ERROR_QUIET
  RESULT_VARIABLE _result)
if(NOT _result EQUAL 0 OR _revision STREQUAL "")
  set(_revision "unknown")
endif()
set(_text "#pragma once\n#define TALUS_GIT_REVISION \"${_revision}\"\n")
if(EXISTS ${OUTPUT})
  file(READ ${OUTPUT} _old)
endif()
if(NOT "${_old}" STREQUAL "${_text}")
  file(WRITE ${OUTPUT} "${_text}")
endif()
