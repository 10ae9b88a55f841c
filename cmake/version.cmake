# Run at every build (cmake -P): writes generated/beamid/version.h only when its content changes, so a commit or an
# edit is reflected without reconfiguring and an unchanged tree triggers no rebuild.
# BEAMID_GIT_COMMIT is the last commit that changed what the programs compute: src/, studies/, cmake/ and
# CMakeLists.txt. Tests, plot scripts, prose and generated outputs (results/, plots/, REPORT.md) are left out, so
# committing regenerated results, a new test or an edited README neither changes the provenance stamped into the
# results nor invalidates a study's store. BEAMID_GIT_DIRTY is 1 when those paths have uncommitted changes.
set(spec src studies cmake CMakeLists.txt ":(glob,exclude)**/*.md")
execute_process(COMMAND git log -1 --format=%h --abbrev=12 -- ${spec} WORKING_DIRECTORY ${SOURCE_DIR}
                OUTPUT_VARIABLE commit OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE rc)
if(NOT rc EQUAL 0 OR NOT commit)
  set(commit "unknown")
endif()
execute_process(COMMAND git status --porcelain --untracked-files=no -- ${spec} WORKING_DIRECTORY ${SOURCE_DIR}
                OUTPUT_VARIABLE status OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
if(status)
  set(dirty 1)
else()
  set(dirty 0)
endif()
set(text "// Generated at build time by cmake/version.cmake: what every program reports it ran.
#pragma once
#define BEAMID_VERSION \"${VERSION}\"
#define BEAMID_GIT_COMMIT \"${commit}\"
#define BEAMID_GIT_DIRTY ${dirty}
")
set(path ${OUTPUT_DIR}/beamid/version.h)
if(EXISTS ${path})
  file(READ ${path} old)
else()
  set(old "")
endif()
if(NOT old STREQUAL text)
  file(WRITE ${path} "${text}")
endif()
