# Writes OUT = `#define STENTOR_GIT_DESCRIBE "<git describe --always --dirty --tags>"` (empty
# outside a git checkout or without git), and only when that text changed, so that
# `stentor --version` names the sources it was built from without recompiling main.cpp at
# every build. Run by the target stentor_git at every build (CMakeLists.txt).
#   cmake -DGIT=<git or empty> -DSRC=<source dir> -DOUT=<header> -P GitDescribe.cmake
set(describe "")
if(GIT)
  execute_process(COMMAND ${GIT} describe --always --dirty --tags WORKING_DIRECTORY ${SRC}
                  OUTPUT_VARIABLE describe OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    set(describe "")
  endif()
endif()
set(text "#define STENTOR_GIT_DESCRIBE \"${describe}\"\n")
set(old "")
if(EXISTS ${OUT})
  file(READ ${OUT} old)
endif()
if(NOT old STREQUAL text)
  file(WRITE ${OUT} "${text}")
endif()
