# Writes OUT (a .cpp defining btob::build::git_commit) from `git rev-parse HEAD` of SRC, at every build, and
# touches OUT only when the commit changed, so a commit re-links the binary but does not rebuild the rest.
# Usage: cmake -DSRC=<source dir> -DOUT=<file.cpp> -P GitCommit.cmake
execute_process(COMMAND git rev-parse --short=12 HEAD WORKING_DIRECTORY ${SRC}
                OUTPUT_VARIABLE commit OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
if(NOT commit)
  set(commit "unknown")
endif()
set(text "// Generated at build time by cmake/GitCommit.cmake: the commit the binary was built from.\n\
namespace btob::build {\nextern const char* const git_commit;\nconst char* const git_commit = \"${commit}\";\n}  // namespace btob::build\n")
if(EXISTS ${OUT})
  file(READ ${OUT} old)
else()
  set(old "")
endif()
if(NOT old STREQUAL text)
  file(WRITE ${OUT} "${text}")
endif()
