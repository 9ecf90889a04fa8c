// MuJoCo 2.2.2 twin of a ball_model (docs/design.md, "Pitfalls of the dependencies":
// handled here: no mj_addBufferVFS, a 2 MB mjVFS, exiting error handler).
#include "mujoco_ball.h"

#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <memory>

#include "common.h"

namespace bv {

namespace {

// MuJoCo's default error handler prints, waits for Enter and exits. Ours
// jumps back to the guarded call that is running; MuJoCo is C, so only C
// frames and our trivially destructible lambda frames are skipped.
thread_local std::jmp_buf *g_jump = nullptr;
thread_local std::string g_error;
thread_local long g_warnings = 0;

extern "C" void on_mj_error(const char *msg) {
  g_error = msg ? msg : "(null)";
  if (g_jump) std::longjmp(*g_jump, 1);
  // An error outside a guarded call: returning would let MuJoCo go on with
  // a broken state, so stop here with the message.
  std::fprintf(stderr, "ball_validate: MuJoCo error outside a guarded call: %s\n", g_error.c_str());
  std::abort();
}

extern "C" void on_mj_warning(const char *msg) {
  ++g_warnings;
  g_error = std::string("warning: ") + (msg ? msg : "(null)");
}

// Runs f with MuJoCo errors turned into a false return.
template <class F>
bool guarded(F &&f) {
  std::jmp_buf jb;
  std::jmp_buf *saved = g_jump;
  g_jump = &jb;
  if (setjmp(jb) != 0) {
    g_jump = saved;
    return false;
  }
  f();
  g_jump = saved;
  return true;
}

}  // namespace

void mj_install_handlers() {
  mju_user_error = on_mj_error;
  mju_user_warning = on_mj_warning;
}

const std::string &mj_last_error() { return g_error; }

bool mj_handlers_selftest() {
  mj_install_handlers();
  g_error.clear();
  bool returned = guarded([] { mju_error("ball_validate handler self-test"); });
  return !returned && g_error == "ball_validate handler self-test";
}
long mj_warning_count() { return g_warnings; }

std::string mjcf_from_model(const ball_model &model, int integrator, double timestep) {
  // eq 2: the drag acts on the horizontal axes only, as joint damping beta.
  double beta = (model.effects & BALL_EFFECT_DRAG) ? model.air_friction : 0.0;
  double r = model.radius > 0.033 ? model.radius : 0.033;
  double inertia = 0.4 * model.mass * r * r;  // unused by slide joints; must be valid
  return fmt(
      "<mujoco model=\"libball\">\n"
      "  <option timestep=\"%.17g\" gravity=\"0 %.17g 0\" integrator=\"%s\">\n"
      "    <flag contact=\"disable\" constraint=\"disable\"/>\n"
      "  </option>\n"
      "  <worldbody>\n"
      "    <body name=\"ball\">\n"
      "      <inertial pos=\"0 0 0\" mass=\"%.17g\" diaginertia=\"%.17g %.17g %.17g\"/>\n"
      "      <joint name=\"x\" type=\"slide\" axis=\"1 0 0\" damping=\"%.17g\"/>\n"
      "      <joint name=\"y\" type=\"slide\" axis=\"0 1 0\" damping=\"0\"/>\n"
      "      <joint name=\"z\" type=\"slide\" axis=\"0 0 1\" damping=\"%.17g\"/>\n"
      "    </body>\n"
      "  </worldbody>\n"
      "</mujoco>\n",
      timestep, -model.gravity, integrator == mjINT_RK4 ? "RK4" : "Euler", model.mass, inertia,
      inertia, inertia, beta, beta);
}

MjBall::~MjBall() {
  if (d_) mj_deleteData(d_);
  if (m_) mj_deleteModel(m_);
}

bool MjBall::load(const ball_model &model, int integrator, double timestep, std::string *error) {
  mj_install_handlers();
  std::string xml = mjcf_from_model(model, integrator, timestep);
  // mjVFS is about 2 MB: on the heap. MuJoCo 2.2.2 has no mj_addBufferVFS:
  // make an empty file of length + 1 and copy the NUL-terminated text in.
  std::unique_ptr<mjVFS> vfs(new mjVFS);
  mj_defaultVFS(vfs.get());
  char err[1000] = "";
  mjModel *m = nullptr;
  bool ok = guarded([&] {
    if (mj_makeEmptyFileVFS(vfs.get(), "ball.xml", static_cast<int>(xml.size()) + 1) != 0) return;
    int i = mj_findFileVFS(vfs.get(), "ball.xml");
    if (i < 0) return;
    std::memcpy(vfs->filedata[i], xml.c_str(), xml.size() + 1);
    m = mj_loadXML("ball.xml", vfs.get(), err, sizeof err);
  });
  mj_deleteVFS(vfs.get());
  if (!ok || !m) {
    if (error) *error = std::string("MuJoCo could not load the model: ") + (ok ? err : g_error);
    if (m) mj_deleteModel(m);
    return false;
  }
  if (d_) mj_deleteData(d_);
  if (m_) mj_deleteModel(m_);
  m_ = m;
  d_ = mj_makeData(m_);
  // The twin must hold exactly the model's numbers (the XML carries 17 digits).
  double beta = (model.effects & BALL_EFFECT_DRAG) ? model.air_friction : 0.0;
  std::string bad;
  if (m_->nq != 3 || m_->nv != 3) bad = "nq/nv";
  else if (m_->body_mass[1] != model.mass) bad = "mass";
  else if (m_->opt.gravity[0] != 0.0 || m_->opt.gravity[1] != -model.gravity || m_->opt.gravity[2] != 0.0)
    bad = "gravity";
  else if (m_->dof_damping[0] != beta || m_->dof_damping[1] != 0.0 || m_->dof_damping[2] != beta)
    bad = "damping";
  else if (!(m_->opt.disableflags & mjDSBL_CONTACT) || !(m_->opt.disableflags & mjDSBL_CONSTRAINT))
    bad = "flags";
  else if (m_->opt.integrator != integrator)
    bad = "integrator";
  if (!bad.empty()) {
    if (error) *error = "MuJoCo model differs from the ball_model in " + bad;
    return false;
  }
  return true;
}

bool MjBall::reset(ball_vec3 p, ball_vec3 v, double timestep) {
  return guarded([&] {
    mj_resetData(m_, d_);
    m_->opt.timestep = timestep;
  }) && set_state(p, v);
}

bool MjBall::set_state(ball_vec3 p, ball_vec3 v) {
  return guarded([&] {
    d_->time = 0.0;
    d_->qpos[0] = p.x;
    d_->qpos[1] = p.y;
    d_->qpos[2] = p.z;
    d_->qvel[0] = v.x;
    d_->qvel[1] = v.y;
    d_->qvel[2] = v.z;
    mj_forward(m_, d_);
  });
}

bool MjBall::step(long n) {
  long w0 = g_warnings;
  bool ok = guarded([&] {
    for (long i = 0; i < n; i++) mj_step(m_, d_);
  });
  for (int i = 0; i < mjNWARNING; i++)
    if (d_->warning[i].number) {
      g_error = fmt("MuJoCo data warning %d (info %d)", i, d_->warning[i].lastinfo);
      return false;
    }
  return ok && g_warnings == w0;
}

}  // namespace bv
