# Run at every build (cmake -P): writes generated/beamid/version.h only when its content changes, so a commit or an
# edit is reflected without reconfiguring and an unchanged tree triggers no rebuild.
# BEAMID_GIT_COMMIT is the last commit that changed the code, studies, tests or build files. Excluded: generated
# outputs (results/, REPORT.md), the plots (pure functions of results/: their scripts draw, they compute nothing)
# and prose (*.md), so committing regenerated results or editing documentation does not change the provenance
# stamped into the results, nor invalidate a study's store. BEAMID_GIT_DIRTY is 1 when those paths have
# uncommitted changes.
set(spec . ":(exclude)results" ":(exclude)plots" ":(glob,exclude)**/*.md")
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
