# SPDX-License-Identifier: GPL-3.0-or-later
# Writes OUT (a .cpp defining btob::build::git_commit and btob::build::git_dirty) from the git state of SRC, at
# every build, and touches OUT only when it changed, so a commit re-links the binary but does not rebuild the rest.
# git_dirty is "yes" when the tree the binary is compiled from differs from the commit: tracked files with
# uncommitted changes anywhere but results/ (a regeneration rewrites results/), or untracked files under src/ and
# cmake/ (source globs pick them up).  Recorded at build time: a binary built from a dirty tree stays dirty
# whatever the tree looks like when it runs.
# Usage: cmake -DSRC=<source dir> -DOUT=<file.cpp> -P GitCommit.cmake
execute_process(COMMAND git rev-parse --short=12 HEAD WORKING_DIRECTORY ${SRC}
                OUTPUT_VARIABLE commit OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
set(dirty "unknown")
if(NOT commit)
  set(commit "unknown")
else()
  execute_process(COMMAND git status --porcelain --untracked-files=no -- . ":(exclude)results"
                  WORKING_DIRECTORY ${SRC} OUTPUT_VARIABLE tracked RESULT_VARIABLE rc1 ERROR_QUIET)
  execute_process(COMMAND git status --porcelain --untracked-files=all -- src cmake
                  WORKING_DIRECTORY ${SRC} OUTPUT_VARIABLE untracked RESULT_VARIABLE rc2 ERROR_QUIET)
  if(rc1 EQUAL 0 AND rc2 EQUAL 0)
    if(tracked STREQUAL "" AND untracked STREQUAL "")
      set(dirty "no")
    else()
      set(dirty "yes")
    endif()
  endif()
endif()
set(text "// Generated at build time by cmake/GitCommit.cmake: the commit the binary was built from, and whether the\n\
// tree had uncommitted changes then.\n\
namespace btob::build {\nextern const char* const git_commit;\nextern const char* const git_dirty;\n\
const char* const git_commit = \"${commit}\";\nconst char* const git_dirty = \"${dirty}\";\n}  // namespace btob::build\n")
if(EXISTS ${OUT})
  file(READ ${OUT} old)
else()
  set(old "")
endif()
if(NOT old STREQUAL text)
  file(WRITE ${OUT} "${text}")
endif()
