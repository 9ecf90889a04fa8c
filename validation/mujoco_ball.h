// The MuJoCo twin of a ball_model: the same ODEs (eq 1, 2) as an MJCF model
// built in memory and loaded through MuJoCo's virtual file system.
#ifndef BALL_VALIDATION_MUJOCO_BALL_H
#define BALL_VALIDATION_MUJOCO_BALL_H

#include <mujoco/mujoco.h>

#include <string>

#include "ball/ball.h"

namespace bv {

// Installs MuJoCo's error and warning handlers (once): an error inside a
// guarded call becomes a false return with the message, never an exit;
// every warning is counted.
void mj_install_handlers();
const std::string &mj_last_error();
long mj_warning_count();
// Raises a MuJoCo error inside a guarded call: true if it came back as a
// failure with its message (and the process is still here).
bool mj_handlers_selftest();

// The MJCF text for model: one body on three slide joints x, y, z with the
// ball's mass, joint damping beta on x and z (eq 2: m x'' = -beta x'),
// gravity (0, -g, 0) (eq 1), contacts and constraints disabled.
std::string mjcf_from_model(const ball_model &model, int integrator, double timestep);

// A loaded twin: model and data, freed together.
class MjBall {
 public:
  MjBall() = default;
  MjBall(const MjBall &) = delete;
  MjBall &operator=(const MjBall &) = delete;
  ~MjBall();

  // Builds the MJCF, loads it through a VFS and checks that MuJoCo holds
  // exactly the model's numbers; false with *error set on any failure.
  bool load(const ball_model &model, int integrator, double timestep, std::string *error);

  // Sets the state (time 0) and the step; false on a MuJoCo error.
  bool reset(ball_vec3 p, ball_vec3 v, double timestep);
  // Sets the state (time 0) without clearing the rest of mjData (reset()
  // clears MuJoCo's whole arena, which costs more than a short flight's
  // steps); the steps that follow are reset()'s to the bit here, as the twin
  // has no contacts or constraints to warm-start. false on a MuJoCo error.
  bool set_state(ball_vec3 p, ball_vec3 v);
  // Changes the step between two calls of step().
  bool set_step(double timestep) {
    m_->opt.timestep = timestep;
    return true;
  }
  // n steps of mj_step; false on a MuJoCo error or warning.
  bool step(long n);

  ball_vec3 position() const { return {d_->qpos[0], d_->qpos[1], d_->qpos[2]}; }
  ball_vec3 velocity() const { return {d_->qvel[0], d_->qvel[1], d_->qvel[2]}; }
  double time() const { return d_->time; }
  mjModel *model() const { return m_; }
  mjData *data() const { return d_; }

 private:
  mjModel *m_ = nullptr;
  mjData *d_ = nullptr;
};

}  // namespace bv

#endif  // BALL_VALIDATION_MUJOCO_BALL_H
