# The canonical moments of the snapshot regression: one golden PNG each in
# tests/render/golden/NAME.png, 320x240. A case is
#   NAME SCENE TIME CAMERA TRAIL MARKERS
# SCENE is relative to the source tree; TRAIL and MARKERS in s (ballrender's
# --trail and --markers). Times sit just after the event they show (from
# ballsim's event lines), so the event's marker is in the picture.
set(BALL_GOLDEN_SIZE 320x240)
# The comparison, and why these numbers: goldens.cmake and docs/render.md.
set(BALL_GOLDEN_TOLERANCE 8)
set(BALL_GOLDEN_MAX_PIXELS 20)
set(BALL_GOLDEN_CASES
  # a serve's first bounce, t = 0.728 s, at x = 14.92 m
  "floor_bounce libball/scenes/tennis.yaml 0.75 side 0.75 1"
  # a low ball into the net at t = 0.498 s, from the scene's own camera
  "net_hit tests/render/net_hit.yaml 0.55 umpire 1 1"
  # level easy: racket 1 returns the ball at t = 0.933 s (sphere test, autonomous)
  "racket_easy libball/scenes/rally_easy.yaml 0.95 behind1 0.5 1"
  # level mid: racket 0's first stroke at t = 0.5 s (disc test, mixed)
  "racket_mid libball/scenes/rally_mid.yaml 0.55 behind0 0.5 1"
  # level advanced: racket 1 at t = 1.317 s (disc test, real normal, physical)
  "racket_advanced libball/scenes/rally_advanced.yaml 1.35 side 0.5 1"
  # the dropped basketball at rest on the floor (its last bounce ends before 3 s)
  "ball_at_rest libball/scenes/dropped_ball.yaml 5.5 side 0 1"
  # the football off the wall at t = 0.652 s
  "wall_rebound libball/scenes/football_wall.yaml 0.7 side 0.7 1"
  # six seconds of the mid rally, every stroke's arc
  "long_trail libball/scenes/rally_mid.yaml 6.0 side 6 6"
)
