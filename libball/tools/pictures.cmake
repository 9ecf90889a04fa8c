# The pictures of the docs, rendered afresh from the example scenes (see
# docs/render.md, "Pictures in the docs"); `./run pictures` runs it:
#   cmake -DBALLRENDER=... -DSOURCE=... -DWORK=... [-DAPNGASM=apngasm] -P pictures.cmake
# Stills go to docs/img/NAME.png; the rally at the top of the README is an
# animated PNG (APNG) put together by apngasm (Debian's apngasm package).
cmake_minimum_required(VERSION 3.20)
set(img ${SOURCE}/docs/img)
file(MAKE_DIRECTORY ${img} ${WORK})
if(NOT APNGASM)
  set(APNGASM apngasm)
endif()

# NAME SCENE TIMES CAMERA TRAIL MARKERS SIZE
set(stills
  "serve_bounce libball/scenes/tennis.yaml 0.8 side 0.8 1 480x300"
  "net_hit tests/render/net_hit.yaml 0.55 umpire 1 1 480x300"
  "wall_rebound libball/scenes/football_wall.yaml 0.75 side 0.75 1 480x300"
  "dropped_ball libball/scenes/dropped_ball.yaml 4 side 4 4 480x300"
  "rally_side libball/scenes/rally_mid.yaml 2.2 side 1.5 1 320x240"
  "rally_top libball/scenes/rally_mid.yaml 2.2 top 1.5 1 320x240"
  "rally_behind0 libball/scenes/rally_mid.yaml 2.2 behind0 1.5 1 320x240"
  "rally_behind1 libball/scenes/rally_mid.yaml 2.2 behind1 1.5 1 320x240"
  "racket_advanced libball/scenes/rally_advanced.yaml 1.35 behind1 0.8 1 480x300"
)

function(render out)
  file(REMOVE_RECURSE ${out})
  execute_process(COMMAND ${BALLRENDER} ${ARGN} --out ${out} WORKING_DIRECTORY ${SOURCE}
    RESULT_VARIABLE rc OUTPUT_VARIABLE o ERROR_VARIABLE e)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "ballrender ${ARGN}: ${o}${e}")
  endif()
endfunction()

foreach(s ${stills})
  string(REPLACE " " ";" a "${s}")
  list(GET a 0 name)
  list(GET a 1 scene)
  list(GET a 2 time)
  list(GET a 3 camera)
  list(GET a 4 trail)
  list(GET a 5 markers)
  list(GET a 6 size)
  render(${WORK}/${name} ${scene} --times ${time} --camera ${camera} --trail ${trail} --markers ${markers}
    --size ${size})
  file(GLOB f ${WORK}/${name}/t*.png)
  file(COPY_FILE ${f} ${img}/${name}.png)
  message(STATUS "docs/img/${name}.png")
endforeach()

# The README's rally: rally_mid from the side, 10 frames a second for 6 s.
render(${WORK}/rally ${SOURCE}/libball/scenes/rally_mid.yaml --every 0.1 --duration 6 --camera side
  --size 320x200 --trail 1 --markers 0.5)
file(GLOB frames ${WORK}/rally/t*.png)
list(SORT frames)
file(REMOVE_RECURSE ${WORK}/seq)
file(MAKE_DIRECTORY ${WORK}/seq)
set(k 1)
foreach(f ${frames})
  string(LENGTH "${k}" n)
  set(name "000${k}")
  math(EXPR cut "${n} + 3 - 4")
  string(SUBSTRING "${name}" ${cut} 4 name)
  file(COPY_FILE ${f} ${WORK}/seq/frame${name}.png)
  math(EXPR k "${k} + 1")
endforeach()
execute_process(COMMAND ${APNGASM} ${img}/rally.png ${WORK}/seq/frame0001.png 1 10
  RESULT_VARIABLE rc OUTPUT_VARIABLE o ERROR_VARIABLE e)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "apngasm: ${o}${e}")
endif()
list(LENGTH frames n)
message(STATUS "docs/img/rally.png (animated, ${n} frames)")
