# Run at every build (sim/CMakeLists.txt): writes OUT from IN with the source tree's git
# revision. configure_file rewrites OUT only when its text changes, so a build at the same
# revision recompiles nothing, and a build after a commit (or an edit) always records it —
# a revision read once at configure time went stale with every commit.
# Inputs: SOURCE_DIR, PROJECT_VERSION, IN, OUT.
execute_process(COMMAND git rev-parse --short=12 HEAD
                WORKING_DIRECTORY ${SOURCE_DIR}
                OUTPUT_VARIABLE BSMPM_GIT_REVISION
                OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
if(NOT BSMPM_GIT_REVISION)
  set(BSMPM_GIT_REVISION "unknown")
else()
  # Uncommitted changes to tracked files: name them by a hash of the diff, so two different
  # edits of the same revision are two versions (a study reruns its cases, a resume refuses).
  execute_process(COMMAND git diff HEAD
                  WORKING_DIRECTORY ${SOURCE_DIR}
                  OUTPUT_VARIABLE diff ERROR_QUIET)
  if(diff)
    string(SHA1 diff_hash "${diff}")
    string(SUBSTRING "${diff_hash}" 0 8 diff_hash)
    string(APPEND BSMPM_GIT_REVISION "-dirty.${diff_hash}")
  endif()
endif()
configure_file(${IN} ${OUT} @ONLY)
