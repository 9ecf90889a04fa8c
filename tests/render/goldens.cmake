# Renders the golden moments afresh and compares them with the goldens, or
# (MODE=update) writes new goldens. Run by ctest (one CASE each) and by
# `./run goldens`:
#   cmake -DBALLRENDER=... -DPROBE=... -DSOURCE=... -DWORK=... [-DCASE=name]
#         [-DMODE=check|update] -P goldens.cmake
#
# The comparison (golden_cases.cmake; docs/render.md, "Tolerance"): a pixel
# differs when one of its channels is more than BALL_GOLDEN_TOLERANCE = 8 of
# 255 apart, and a
# frame fails when more than BALL_GOLDEN_MAX_PIXELS = 20 of its 76800 pixels
# differ. llvmpipe is exact on one machine but not across CPUs: other SIMD
# widths round interpolated colours differently by a level or two (far
# under 8), and now and then a sample right on a triangle's edge falls the
# other way, which after the 2 x 2 averaging changes an edge pixel by a
# quarter of the contrast there (a handful of pixels, under 20). A ball 5 cm
# off moves its sphere and its shadow by 2 pixels or more in these views,
# which changes far more than 20 pixels (tests/render/tests.cmake,
# render_golden_detects_moved_ball).
cmake_minimum_required(VERSION 3.20)
include(${CMAKE_CURRENT_LIST_DIR}/golden_cases.cmake)
if(NOT MODE)
  set(MODE check)
endif()
set(golden_dir ${SOURCE}/tests/render/golden)

# Renders one case into WORK/NAME/; sets FRAME to the PNG it wrote.
function(render_case name scene time camera trail markers)
  set(out ${WORK}/${name})
  file(REMOVE_RECURSE ${out})
  file(MAKE_DIRECTORY ${WORK})
  execute_process(COMMAND ${BALLRENDER} ${scene} --times ${time} --camera ${camera} --size ${BALL_GOLDEN_SIZE}
      --trail ${trail} --markers ${markers} --out ${out}
    WORKING_DIRECTORY ${SOURCE} RESULT_VARIABLE rc OUTPUT_VARIABLE o ERROR_VARIABLE e)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${name}: ballrender failed (${rc}):\n${o}${e}")
  endif()
  file(GLOB frames ${out}/t*.png)
  list(LENGTH frames n)
  if(NOT n EQUAL 1)
    message(FATAL_ERROR "${name}: expected one frame in ${out}, got ${n}")
  endif()
  set(FRAME ${frames} PARENT_SCOPE)
endfunction()

set(failed "")
set(done 0)
foreach(c ${BALL_GOLDEN_CASES})
  string(REPLACE " " ";" args "${c}")
  list(GET args 0 name)
  if(CASE AND NOT CASE STREQUAL name)
    continue()
  endif()
  math(EXPR done "${done} + 1")
  list(SUBLIST args 1 5 rest)
  render_case(${name} ${rest})
  if(MODE STREQUAL update)
    file(COPY_FILE ${FRAME} ${golden_dir}/${name}.png)
    message(STATUS "golden ${name}: ${golden_dir}/${name}.png")
    continue()
  endif()
  if(NOT EXISTS ${golden_dir}/${name}.png)
    message(FATAL_ERROR "${name}: no golden ${golden_dir}/${name}.png (./run goldens makes it)")
  endif()
  string(REGEX REPLACE "\\.png$" ".diff.png" diff "${FRAME}")
  execute_process(COMMAND ${PROBE} compare ${golden_dir}/${name}.png ${FRAME} ${diff}
      ${BALL_GOLDEN_TOLERANCE} ${BALL_GOLDEN_MAX_PIXELS}
    RESULT_VARIABLE rc OUTPUT_VARIABLE o ERROR_VARIABLE e)
  message(STATUS "${name}: ${o}${e}")
  if(NOT rc EQUAL 0)
    list(APPEND failed ${name})
  endif()
endforeach()
if(done EQUAL 0)
  # no case compared (none listed, or CASE names none): that is no pass
  message(FATAL_ERROR "no golden case ${CASE} in golden_cases.cmake")
endif()
if(failed)
  message(FATAL_ERROR "golden frames that differ: ${failed}")
endif()
