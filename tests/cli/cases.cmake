# One ballsim case per run: cmake -DBALLSIM=... -DSCENES=... -DHERE=... -DWORK=... -DCASE=name -P cases.cmake
# Numbers computed by hand are explained where they are checked.
cmake_minimum_required(VERSION 3.20)

file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")

# Runs ballsim with the given arguments; sets RC, OUT and ERR.
macro(ballsim)
  execute_process(COMMAND "${BALLSIM}" ${ARGN} WORKING_DIRECTORY "${WORK}"
    RESULT_VARIABLE RC OUTPUT_VARIABLE OUT ERROR_VARIABLE ERR)
endmacro()

include(${CMAKE_CURRENT_LIST_DIR}/../expect.cmake)

# lo <= value <= hi, as doubles.
function(expect_between what value lo hi)
  if(NOT (value GREATER_EQUAL lo AND value LESS_EQUAL hi))
    fail("${what} = ${value} not within [${lo}, ${hi}]")
  endif()
endfunction()

# The event lines of OUT, in order, into the list EVENTS.
macro(collect_events)
  string(REGEX MATCHALL "event [^\n]*" EVENTS "${OUT}")
endmacro()

# Field NAME of an event line (e.g. point=1,2,3 -> "1,2,3"), into VAR; a
# comma-separated value is also split into VAR_0, VAR_1, VAR_2.
function(event_field line name var)
  if(NOT line MATCHES " ${name}=([^ ]+)")
    fail("no ${name}= in: ${line}")
  endif()
  set(v "${CMAKE_MATCH_1}")
  set(${var} "${v}" PARENT_SCOPE)
  string(REPLACE "," ";" parts "${v}")
  list(LENGTH parts n)
  if(n EQUAL 3)
    list(GET parts 0 p0)
    list(GET parts 1 p1)
    list(GET parts 2 p2)
    set(${var}_0 "${p0}" PARENT_SCOPE)
    set(${var}_1 "${p1}" PARENT_SCOPE)
    set(${var}_2 "${p2}" PARENT_SCOPE)
  endif()
endfunction()

# Lines of a file into the list LINES (no empty last line); with a count,
# fails unless there are exactly that many.
function(read_lines file)
  file(STRINGS "${file}" lines)
  list(LENGTH lines n)
  if(ARGC GREATER 1 AND NOT n EQUAL ARGV1)
    get_filename_component(name "${file}" NAME)
    fail("${name} has ${n} lines, expected ${ARGV1}")
  endif()
  set(LINES "${lines}" PARENT_SCOPE)
endfunction()

# How often the ball centre crosses the plane x = net_x in a --out CSV must
# be within [lo, hi].
function(expect_net_crossings file net_x lo hi)
  file(STRINGS "${file}" rows)
  list(REMOVE_AT rows 0)
  set(n 0)
  set(prev "")
  foreach(row IN LISTS rows)
    string(REPLACE "," ";" c "${row}")
    list(GET c 1 x)
    if(x GREATER net_x)
      set(side 1)
    else()
      set(side 0)
    endif()
    if(NOT prev STREQUAL "" AND NOT side EQUAL prev)
      math(EXPR n "${n} + 1")
    endif()
    set(prev ${side})
  endforeach()
  expect_between("net crossings" "${n}" "${lo}" "${hi}")
endfunction()

# The racket events of OUT into RACKETS; fails unless there are at least
# min_count and they alternate between rackets 0 and 1, starting with 0.
function(expect_rally min_count)
  string(REGEX MATCHALL "event [^\n]* kind=racket [^\n]*" hits "${OUT}")
  list(LENGTH hits n)
  if(n LESS min_count)
    fail("${n} racket events, expected at least ${min_count}")
  endif()
  set(want 0)
  foreach(h IN LISTS hits)
    if(NOT h MATCHES "kind=racket index=${want} ")
      fail("racket events do not alternate 0, 1, 0, ...: ${h}")
    endif()
    math(EXPR want "1 - ${want}")
  endforeach()
  set(RACKETS "${hits}" PARENT_SCOPE)
endfunction()

# The samples line of OUT: SAMPLES_ARRIVED, _ACCEPTED, _DUPLICATE, _STALE.
macro(read_samples)
  if(NOT OUT MATCHES "\nsamples: arrived=([0-9]+) accepted=([0-9]+) duplicate=([0-9]+) stale=([0-9]+) invalid=0\n")
    fail("no samples line with invalid=0")
  endif()
  set(SAMPLES_ARRIVED ${CMAKE_MATCH_1})
  set(SAMPLES_ACCEPTED ${CMAKE_MATCH_2})
  set(SAMPLES_DUPLICATE ${CMAKE_MATCH_3})
  set(SAMPLES_STALE ${CMAKE_MATCH_4})
  math(EXPR sum "${SAMPLES_ACCEPTED} + ${SAMPLES_DUPLICATE} + ${SAMPLES_STALE}")
  if(NOT sum EQUAL SAMPLES_ARRIVED)
    fail("accepted + duplicate + stale = ${sum}, not arrived = ${SAMPLES_ARRIVED}")
  endif()
endmacro()

set(summary_re "\nsummary: frames=[0-9]+ time=[0-9.]+ events=[0-9]+ floor=[0-9]+ net=[0-9]+ wall=[0-9]+ racket=[0-9]+ sounds=[0-9]+\nsamples: arrived=[0-9]+ accepted=[0-9]+ duplicate=[0-9]+ stale=[0-9]+ invalid=0\nfinal: position=[^ ]+ velocity=[^ ]+ spin=[^ ]+ grounded=[01]\nwarnings: event_overflow=0 contact_limit=0 stale_racket=0\n$")

# Runs ballsim with the given arguments; expects exit status 0 and the
# summary block at the end of stdout. Sets RC, OUT and ERR.
function(run_scene)
  ballsim(${ARGN})
  expect_rc(0)
  expect_out("${summary_re}")
  set(RC "${RC}" PARENT_SCOPE)
  set(OUT "${OUT}" PARENT_SCOPE)
  set(ERR "${ERR}" PARENT_SCOPE)
endfunction()

# Runs ballsim with the arguments before STATUS; expects that exit status
# and stderr matching the STDERR regex. Sets RC, OUT and ERR.
function(expect_failure)
  cmake_parse_arguments(PARSE_ARGV 0 A "" "STATUS;STDERR" "")
  ballsim(${A_UNPARSED_ARGUMENTS})
  expect_rc(${A_STATUS})
  expect_err("${A_STDERR}")
  set(RC "${RC}" PARENT_SCOPE)
  set(OUT "${OUT}" PARENT_SCOPE)
  set(ERR "${ERR}" PARENT_SCOPE)
endfunction()

if(CASE STREQUAL "help")
  ballsim(--help)
  expect_rc(0)
  foreach(word "usage: ballsim \\[SCENE\\]" "--fps N" "--duration S" "--scheme MODE" "--out FILE"
               "--format FMT" "t,px,py,pz,vx,vy,vz,sx,sy,sz" "Exit status")
    expect_out("${word}")
  endforeach()
  ballsim(-h)
  expect_rc(0)
  expect_out("^usage: ballsim")

elseif(CASE STREQUAL "default_is_tennis")
  # No scene: the built-in tennis serve, identical to scenes/tennis.yaml.
  run_scene(--out builtin.csv)
  expect_out("^scene: tennis \\(built-in\\) scheme=exact fps=60 ")
  string(REGEX REPLACE "^[^\n]*\n" "" builtin_body "${OUT}")
  ballsim("${SCENES}/tennis.yaml" --out file.csv)
  expect_rc(0)
  string(REGEX REPLACE "^[^\n]*\n" "" file_body "${OUT}")
  if(NOT builtin_body STREQUAL file_body)
    fail("events and summary differ between the built-in scene and tennis.yaml:\n${builtin_body}")
  endif()
  file(READ "${WORK}/builtin.csv" a)
  file(READ "${WORK}/file.csv" b)
  if(NOT a STREQUAL b)
    fail("trajectories differ between the built-in scene and tennis.yaml")
  endif()

elseif(CASE STREQUAL "tennis")
  # The serve crosses the net without touching it and lands in the service
  # box: 11.885 m (net) < x < 18.285 m (service line), 0 < z < 10.97 m.
  run_scene("${SCENES}/tennis.yaml")
  expect_out(" net=0 ")
  collect_events()
  list(LENGTH EVENTS n)
  if(n LESS 1)
    fail("no event")
  endif()
  list(GET EVENTS 0 first)
  if(NOT first MATCHES "kind=floor index=0 ")
    fail("the first event is not the bounce: ${first}")
  endif()
  event_field("${first}" point p)
  expect_between("bounce x" "${p_0}" 11.885 18.285)
  expect_between("bounce z" "${p_2}" 0 10.97)
  expect_between("bounce y (point ball on the floor)" "${p_1}" -0.000001 0.000001)
  event_field("${first}" sound sound)
  expect_between("sound of a 7 m/s bounce" "${sound}" 1 1)

elseif(CASE STREQUAL "football_wall")
  # The kick hits the wall (x = 11 m) first, where the ball centre is one
  # radius before the plane: x = 11 - 0.11 = 10.89 m; eq 6 turns the normal
  # speed around with the wall's damping 0.7. Then it bounces back on the
  # grass and ends sliding (grounded) nearer the kicker.
  run_scene("${SCENES}/football_wall.yaml")
  expect_out(" wall=1 ")
  expect_out("grounded=1\n")
  collect_events()
  list(GET EVENTS 0 first)
  if(NOT first MATCHES "kind=wall index=0 point=10\\.890000,")
    fail("the first event is not the wall hit at x = 10.89: ${first}")
  endif()
  event_field("${first}" point p)
  expect_between("hit height" "${p_1}" 0.11 3.0)
  event_field("${first}" v_in vin)
  event_field("${first}" v_out vout)
  expect_between("v_in x" "${vin_0}" 0.001 100)
  # v_out x = -0.7 v_in x, to the 4 printed decimals
  string(REGEX REPLACE "^-" "" vout_abs "${vout_0}")
  if(NOT vout_0 MATCHES "^-")
    fail("the ball does not come back from the wall: v_out x = ${vout_0}")
  endif()
  # 0.7 * 15.4674 = 10.8272 (the scene's numbers); allow 2e-4 for rounding
  expect_between("|v_out x|" "${vout_abs}" 10.8270 10.8274)
  expect_between("v_in x" "${vin_0}" 15.4672 15.4676)
  list(LENGTH EVENTS n)
  if(n LESS 2)
    fail("no floor bounce after the wall")
  endif()
  list(GET EVENTS 1 second)
  if(NOT second MATCHES "kind=floor ")
    fail("the second event is not a floor bounce: ${second}")
  endif()
  if(NOT OUT MATCHES "final: position=([^,]+),")
    fail("no final position")
  endif()
  expect_between("final x" "${CMAKE_MATCH_1}" 0 10.89)

elseif(CASE STREQUAL "dropped_ball")
  # Dropped from 2 m (centre 1.88 m above the contact height): the impact
  # speed is about sqrt(2 g 1.88) = 6.07 m/s; each bounce keeps 0.75 of it,
  # and 6.07 * 0.75^n < 0.3 m/s (the bounce threshold) first for n = 11:
  # 11 floor events, the last one leaving at 0, then the ball rests on the
  # floor (y = radius = 0.12 m) with zero velocity.
  run_scene("${SCENES}/dropped_ball.yaml")
  expect_out(" events=11 floor=11 net=0 wall=0 ")
  expect_out("final: position=0\\.000000,0\\.120000,0\\.000000 velocity=0\\.000000,0\\.000000,0\\.000000 [^\n]* grounded=1\n")
  collect_events()
  list(GET EVENTS 0 first)
  event_field("${first}" speed_in s)
  expect_between("first impact speed" "${s}" 6.06 6.08)
  list(GET EVENTS -1 last)
  if(NOT last MATCHES "speed_out=0\\.0000 sound=0$")
    fail("the last bounce does not stop the ball quietly: ${last}")
  endif()

elseif(CASE STREQUAL "darts")
  # One hit, on the board (x = 2.37 m, y in [1.5045, 1.9555], z in
  # [-0.2255, 0.2255]), near the bull at 1.73 m; the board takes the speed.
  run_scene("${SCENES}/darts.yaml")
  expect_out(" events=1 floor=0 net=0 wall=1 racket=0 ")
  collect_events()
  list(GET EVENTS 0 hit)
  if(NOT hit MATCHES "kind=wall index=0 point=2\\.370000,")
    fail("not a hit on the board: ${hit}")
  endif()
  event_field("${hit}" point p)
  expect_between("hit height" "${p_1}" 1.70 1.76)
  expect_between("hit z" "${p_2}" -0.2255 0.2255)
  event_field("${hit}" speed_out s)
  expect_between("speed after the hit" "${s}" 0 0.00005)
  expect_out("spin=0\\.000000,0\\.000000,0\\.000000")

elseif(CASE STREQUAL "juggling")
  # Drag-free, by hand (see juggling.yaml): contacts at t = 1.2 s, x = 0.6 m
  # and t = 2.46 s, x = 0.6 + 0.45 * 1.26 = 1.167 m.
  run_scene("${SCENES}/juggling.yaml")
  expect_out("effects=floor,sound\n")
  expect_out("\nevent t=1\\.200000 kind=floor index=0 point=0\\.600000,0\\.035000,0\\.000000 v_in=0\\.5000,-6\\.8670,0\\.0000 v_out=[^ ]+,6\\.1803,0\\.0000 ")
  expect_out("\nevent t=2\\.460000 kind=floor index=0 point=1\\.167000,0\\.035000,0\\.000000 ")
  expect_out(" events=2 floor=2 ")

elseif(CASE STREQUAL "juggling_exact_at_any_fps")
  # The exact scheme does not depend on the frame rate: the same two
  # contacts, to the printed microsecond and micrometre, at 2, 7 and 1000 Hz.
  foreach(fps 2 7 1000)
    ballsim("${SCENES}/juggling.yaml" --fps ${fps})
    expect_rc(0)
    expect_out("\nevent t=1\\.200000 kind=floor index=0 point=0\\.600000,0\\.035000,0\\.000000 ")
    expect_out("\nevent t=2\\.460000 kind=floor index=0 point=1\\.167000,0\\.035000,0\\.000000 ")
    expect_out(" events=2 floor=2 ")
  endforeach()

elseif(CASE STREQUAL "overrides")
  # --fps 7 --duration 0.5: ceil(0.5 * 7) = 4 frames of 1/7 s
  ballsim("${SCENES}/juggling.yaml" --fps 7 --duration 0.5 --scheme sampled)
  expect_rc(0)
  expect_out("^scene: juggling \\([^)]*juggling.yaml\\) scheme=sampled fps=7 dt=0\\.142857143 frames=4 ")
  expect_out("\nsummary: frames=4 time=0\\.571429 ")
  ballsim("${SCENES}/juggling.yaml" --fps=30 --duration=1)
  expect_rc(0)
  expect_out("^scene: juggling [^\n]* scheme=exact fps=30 [^\n]* frames=30 ")

elseif(CASE STREQUAL "out_csv")
  # 0.1 s at 60 fps: 6 frames, so 7 rows (t = 0 included) under a header.
  ballsim("${SCENES}/tennis.yaml" --duration 0.1 --out traj.csv)
  expect_rc(0)
  read_lines("${WORK}/traj.csv" 8)
  list(GET LINES 0 header)
  if(NOT header STREQUAL "t,px,py,pz,vx,vy,vz,sx,sy,sz")
    fail("bad CSV header: ${header}")
  endif()
  # row 1 is the initial state of tennis.yaml: (-0.5, 2.6, 3), (24, 0, 1.2), 0
  list(GET LINES 1 row)
  string(REPLACE "," ";" c "${row}")
  list(LENGTH c nc)
  if(NOT nc EQUAL 10)
    fail("row has ${nc} columns: ${row}")
  endif()
  set(want 0 -0.5 2.6 3 24 0 1.2 0 0 0)
  foreach(i RANGE 9)
    list(GET c ${i} got)
    list(GET want ${i} w)
    expect_between("t=0 column ${i}" "${got}" "${w}" "${w}")
  endforeach()
  # every row has 10 numbers and t grows by 1/60 s
  foreach(k RANGE 1 7)
    list(GET LINES ${k} row)
    if(NOT row MATCHES "^[-0-9.e+]+(,[-0-9.e+]+)(,[-0-9.e+]+)(,[-0-9.e+]+)(,[-0-9.e+]+)(,[-0-9.e+]+)(,[-0-9.e+]+)(,[-0-9.e+]+)(,[-0-9.e+]+)(,[-0-9.e+]+)$")
      fail("row ${k} is not 10 numbers: ${row}")
    endif()
  endforeach()
  list(GET LINES 7 last)
  string(REPLACE "," ";" c "${last}")
  list(GET c 0 t)
  expect_between("t of the last row" "${t}" 0.0999999999 0.1000000001)
  # drag only before the bounce: vx = 24 e^(-t/b), b = 0.057 / 0.02 = 2.85 s,
  # at t = 0.1: 24 * e^(-0.1/2.85) = 23.17247...
  list(GET c 4 vx)
  expect_between("vx at t = 0.1" "${vx}" 23.1724 23.1726)

elseif(CASE STREQUAL "out_jsonl")
  ballsim("${SCENES}/tennis.yaml" --duration 0.1 --out traj.jsonl)
  expect_rc(0)
  read_lines("${WORK}/traj.jsonl" 7)
  set(num "-?[0-9][-0-9.e+]*")
  foreach(line IN LISTS LINES)
    if(NOT line MATCHES "^{\"t\":${num},\"px\":${num},\"py\":${num},\"pz\":${num},\"vx\":${num},\"vy\":${num},\"vz\":${num},\"sx\":${num},\"sy\":${num},\"sz\":${num}}$")
      fail("not a JSON object with t, px .. sz: ${line}")
    endif()
  endforeach()
  list(GET LINES 0 first)
  if(NOT first MATCHES "^{\"t\":0,\"px\":-0\\.5,\"py\":2\\.6[0-9]*,\"pz\":3,\"vx\":24,\"vy\":0,")
    fail("the first record is not the initial state: ${first}")
  endif()
  # CMake's own JSON reader accepts every line
  foreach(line IN LISTS LINES)
    string(JSON t GET "${line}" t)
  endforeach()
  expect_between("t of the last record" "${t}" 0.0999999999 0.1000000001)

elseif(CASE STREQUAL "format_option")
  # --format wins over the file name
  ballsim("${SCENES}/darts.yaml" --out traj.txt --format jsonl --duration 0.05)
  expect_rc(0)
  read_lines("${WORK}/traj.txt")
  list(GET LINES 0 first)
  if(NOT first MATCHES "^{\"t\":0,")
    fail("--format jsonl did not write JSON Lines: ${first}")
  endif()
  ballsim("${SCENES}/darts.yaml" --out traj.jsonl --format csv --duration 0.05)
  expect_rc(0)
  read_lines("${WORK}/traj.jsonl")
  list(GET LINES 0 first)
  if(NOT first STREQUAL "t,px,py,pz,vx,vy,vz,sx,sy,sz")
    fail("--format csv did not write CSV: ${first}")
  endif()

elseif(CASE STREQUAL "bad_numbers")
  foreach(bad abc 0 -5 60x nan inf 1e999 " 60" "")
    expect_failure("--fps=${bad}" STATUS 2
      STDERR "^ballsim: --fps: expected a number > 0, got \"${bad}\" \\(see ballsim --help\\)\n$")
    if(NOT OUT STREQUAL "")
      fail("printed to stdout before failing")
    endif()
  endforeach()
  foreach(bad -1 0 1s)
    expect_failure(--duration "${bad}" STATUS 2
      STDERR "^ballsim: --duration: expected a number of seconds > 0, got \"${bad}\"")
  endforeach()

elseif(CASE STREQUAL "bad_options")
  expect_failure(--bogus STATUS 2 STDERR "^ballsim: unknown option --bogus ")
  expect_failure(-x STATUS 2 STDERR "^ballsim: unknown option -x ")
  expect_failure("${SCENES}/darts.yaml" "${SCENES}/tennis.yaml" STATUS 2
    STDERR "^ballsim: more than one scene given: ")
  expect_failure(--fps STATUS 2 STDERR "^ballsim: --fps needs a value")
  expect_failure(--scheme fast STATUS 2
    STDERR "^ballsim: --scheme: expected sampled or exact, got \"fast\"")
  expect_failure(--out traj.xml --format xml STATUS 2
    STDERR "^ballsim: --format: expected csv or jsonl, got \"xml\"")
  expect_failure(--out traj.txt STATUS 2 STDERR "^ballsim: --out traj.txt: cannot tell the format")
  expect_failure(--format csv STATUS 2 STDERR "^ballsim: --format needs --out FILE")
  if(EXISTS "${WORK}/traj.txt" OR EXISTS "${WORK}/traj.xml")
    fail("a usage error still wrote a file")
  endif()

elseif(CASE STREQUAL "missing_scene")
  expect_failure(no/such/scene.yaml STATUS 1
    STDERR "^no/such/scene\\.yaml: No such file or directory\n$")

elseif(CASE STREQUAL "rally_easy")
  # Easy level (sphere test, autonomous ball): the rackets hold still, every
  # stroke flies to the partner with V_up = 4 m/s (eq 8), so each racket
  # event leaves with v_out y = 4.0000. 12 s: at least 10 strokes and 10
  # net crossings (15 by design, one stroke every 0.8167 s from t = 0.117 s).
  run_scene("${SCENES}/rally_easy.yaml" --out rally.csv)
  expect_out(" net=0 ")
  expect_rally(10)
  foreach(h IN LISTS RACKETS)
    event_field("${h}" v_out v)
    expect_between("v_out y (V_up, eq 8)" "${v_1}" 4.0 4.0)
  endforeach()
  expect_net_crossings("${WORK}/rally.csv" 11.885 10 1000)
  # 10 Hz for 12 s from two rackets, 80 ms delay: about 2 * 120 samples taken,
  # 5 % lost, 5 % duplicated; a jitter of 150 ms > 100 ms between samples
  # puts some out of order (stale) and delivers some copies (duplicate)
  read_samples()
  expect_between("samples arrived" "${SAMPLES_ARRIVED}" 200 260)
  expect_between("stale samples (out of order)" "${SAMPLES_STALE}" 1 100)
  expect_between("duplicate samples" "${SAMPLES_DUPLICATE}" 1 100)

elseif(CASE STREQUAL "rally_mid")
  # Mid level (disc test with the velocity normal, mixed 0.8): the swings of
  # rally_mid.yaml move at V_friendly, so eq 10 gives V0 y = 0.8 * 4 + 0.2 * 4
  # = 4 m/s, give or take the velocity the 2 mm tracker noise puts into the
  # racket estimate (a difference of two samples 1/60 s apart: sigma =
  # 0.2 * sqrt(2) * 0.002 * 60 = 0.034 m/s; the bound is 4.4 sigma).
  run_scene("${SCENES}/rally_mid.yaml" --out rally.csv)
  expect_out(" net=0 ")
  expect_rally(10)
  foreach(h IN LISTS RACKETS)
    event_field("${h}" v_out v)
    expect_between("v_out y (eq 10)" "${v_1}" 3.85 4.15)
  endforeach()
  expect_net_crossings("${WORK}/rally.csv" 11.885 10 1000)
  read_samples()

elseif(CASE STREQUAL "rally_advanced")
  # Advanced level (disc test with the real normal, physical with spin):
  # the swings brush up along the face, so after the first stroke every ball
  # leaves with spin about z (eq 12), of alternating sign.
  run_scene("${SCENES}/rally_advanced.yaml" --out rally.csv)
  expect_out(" net=0 ")
  expect_rally(10)
  foreach(h IN LISTS RACKETS)
    event_field("${h}" spin_out s)
    string(REGEX REPLACE "^-" "" sz "${s_2}")
    expect_between("|spin_out z| (eq 12)" "${sz}" 0.3 5)
  endforeach()
  expect_net_crossings("${WORK}/rally.csv" 11.885 10 1000)
  read_samples()

elseif(CASE STREQUAL "serve")
  # eq 7: the ball leaves along the racket's velocity (23.5, 0, 5) m/s with
  # its speed |V| = 24.03 m/s, inside [v_min, v_max] = [5, 40], so unclamped;
  # it lands cross-court in the service box: 11.885 < x < 18.285,
  # 5.485 < z < 9.6 (centre line to singles side line).
  run_scene("${SCENES}/serve.yaml")
  expect_out(" net=0 ")
  expect_out("\nevent t=0\.450000 kind=racket index=0 [^\n]* v_out=23\.5000,0\.0000,5\.0000 ")
  collect_events()
  list(GET EVENTS 1 bounce)
  if(NOT bounce MATCHES "kind=floor")
    fail("the serve does not land next: ${bounce}")
  endif()
  event_field("${bounce}" point p)
  expect_between("bounce x" "${p_0}" 11.885 18.285)
  expect_between("bounce z" "${p_2}" 5.485 9.6)

elseif(CASE STREQUAL "smash_6hz")
  # 6 Hz for 3 s: samples 0..18, 19 in all, none rejected. The swept test
  # finds the hit although the disc moves 2.5 m between samples; eq 7 gives
  # the direction of the estimated velocity (2.4, -0.8, 0) / (1/6 s) and the
  # speed v_min = 20 m/s: V0 = 20 (3, -1, 0) / sqrt(10) = (18.9737, -6.3246, 0).
  run_scene("${SCENES}/smash_6hz.yaml")
  expect_out(" racket=1 ")
  expect_out(" net=0 ")
  expect_out("\nsamples: arrived=19 accepted=19 duplicate=0 stale=0 invalid=0\n")
  expect_out("kind=racket index=0 point=7\.99999[0-9],2\.600000,5\.000000 [^\n]* v_out=18\.9737,-6\.3246,0\.0000 [^\n]* speed_out=20\.0000 ")
  collect_events()
  list(GET EVENTS 1 bounce)
  event_field("${bounce}" point p)
  expect_between("smash lands beyond the net, in the court: x" "${p_0}" 11.885 23.77)

elseif(CASE STREQUAL "drop_shot")
  # Physical response with a sliced swing: V0 = (6.5, 3.6, 0) exactly (the
  # swing was solved from eq 11) with backspin S z > 0 (eq 12). It lands just
  # behind the net, and the bounce loses speed to the spin (eq 13, 14, with
  # floorDamping 0.75 and spinFloorDamping 0.8):
  # v_out x = 0.75 v_in x - 0.8 S z = 0.75 * 4.6365 - 1.0696 = 2.4077 m/s,
  # where 0.8 S z is the bounce's spin_out z.
  run_scene("${SCENES}/drop_shot.yaml")
  expect_out(" net=0 ")
  expect_out("kind=racket index=0 [^\n]* v_out=6\.5000,3\.6000,0\.0000 spin_out=-?0\.0000,0\.0000,1\.98[0-9][0-9] ")
  collect_events()
  list(GET EVENTS 1 bounce)
  if(NOT bounce MATCHES "kind=floor")
    fail("the drop shot does not land next: ${bounce}")
  endif()
  event_field("${bounce}" point p)
  expect_between("lands just behind the net: x" "${p_0}" 11.885 14.0)
  event_field("${bounce}" v_in vin)
  event_field("${bounce}" v_out vout)
  event_field("${bounce}" spin_out s)
  expect_between("v_in x" "${vin_0}" 4.6364 4.6366)
  expect_between("spin_out z (0.8 S z)" "${s_2}" 1.0695 1.0697)
  expect_between("v_out x (eq 13)" "${vout_0}" 2.4076 2.4078)

elseif(CASE STREQUAL "bad_script")
  expect_failure("${HERE}/bad_script.yaml" STATUS 1
    STDERR "bad_script\\.yaml:7:13: rackets\\[0\\]\\.script\\.rate: out of range: must be in \\[2, 120\\] Hz, got 200\n$")

elseif(CASE STREQUAL "bad_scenes")
  # file:line:column: field: message, for each kind of error
  expect_failure("${HERE}/bad_range.yaml" STATUS 1
    STDERR "bad_range\\.yaml:5:12: floor\\.damping: out of range: must be in \\[0, 1\\], got 1\\.5\n$")
  expect_failure("${HERE}/bad_key.yaml" STATUS 1
    STDERR "bad_key\\.yaml:4:51: walls\\[1\\]\\.dampnig: unknown key \"dampnig\"\n$")
  expect_failure("${HERE}/bad_type.yaml" STATUS 1
    STDERR "bad_type\\.yaml:3:13: ball\\.position: expected a list of 3 numbers \\[x, y, z\\], got 2 items\n$")
  expect_failure("${HERE}/bad_syntax.yaml" STATUS 1
    STDERR "bad_syntax\\.yaml:4:9: YAML syntax: mapping values are not allowed in this context\n$")
  if(NOT OUT STREQUAL "")
    fail("printed to stdout before failing")
  endif()

elseif(CASE STREQUAL "output_injection")
  # a name with a newline and an escape code cannot fake a line or
  # reach the terminal: printed escaped, one scene line, no raw ESC
  run_scene("${HERE}/injection.yaml")
  expect_out("^scene: a\\\\nevent t=0\\.000000 kind=net index=0 fake\\\\x1b\\[31m \\(")
  string(REGEX MATCHALL "\nevent " fake "${OUT}")
  if(fake)
    fail("a line starting with event was printed")
  endif()
  string(ASCII 27 esc)
  string(FIND "${OUT}" "${esc}" at)
  if(NOT at EQUAL -1)
    fail("a raw escape character was printed")
  endif()

elseif(CASE STREQUAL "big_numbers")
  # 1000 frames of 1000 s falling with no floor: y = -g t^2 / 2 = -4.905e12 m
  # at t = 1e6 s, printed with all its digits (%.17g), not 300 of them
  run_scene("${HERE}/free_fall.yaml" --fps 0.001 --duration 1000000)
  if(NOT OUT MATCHES "final: position=([^,]+),([^,]+),")
    fail("no final position")
  endif()
  expect_between("final y" "${CMAKE_MATCH_2}" -4.91e12 -4.90e12)
  string(REGEX MATCHALL "[^\n]+" lines "${OUT}")
  foreach(l IN LISTS lines)
    string(LENGTH "${l}" n)
    if(n GREATER 400)
      fail("a line of ${n} characters")
    endif()
  endforeach()

elseif(CASE STREQUAL "keys")
  # the field table as the docs' key table: every model key, one row each
  ballsim(--keys)
  expect_rc(0)
  expect_out("^\\| key \\| type \\| unit \\| default \\| range and meaning \\|\n")
  foreach(key gravity floor.damping net.top "walls\\[i\\].hi" "rackets\\[i\\].partner" racket.history ball.spin scheme)
    expect_out("\n\\| `${key}` \\|")
  endforeach()
  expect_out("\n\\| `floor.damping` \\| number \\| 1 \\| 0.75 \\| in \\[0, 1\\]; floorDamping \\(eq 5\\) \\|\n")
else()
  message(FATAL_ERROR "unknown case ${CASE}")
endif()
