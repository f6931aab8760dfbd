#include "ftsense/sim/free_body_accelerometer.hpp"

#include <string>

#include "ftsense/sim/mujoco_model.hpp"

namespace ftsense::sim {

FreeBodyAccelerometer::FreeBodyAccelerometer(const mjModel* m, int site) {
  if (site < 0 || site >= m->nsite) throw ModelError("FreeBodyAccelerometer: no site " + std::to_string(site));
  const int body = m->site_bodyid[site];
  const int joint = m->body_jntadr[body];
  if (joint < 0 || m->body_jntnum[body] != 1 || m->jnt_type[joint] != mjJNT_FREE)
    throw ModelError("FreeBodyAccelerometer: the site's body must hang on exactly one free joint");
  qpos_adr_ = m->jnt_qposadr[joint];
  dof_adr_ = m->jnt_dofadr[joint];
  period_s_ = m->opt.timestep;
  const mjtNum* p = m->site_pos + 3 * site;
  const mjtNum* q = m->site_quat + 4 * site;
  site_in_body_ = Eigen::Vector3d(p[0], p[1], p[2]);
  site_orientation_in_body_ = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized();
  gravity_ = Eigen::Vector3d(m->opt.gravity[0], m->opt.gravity[1], m->opt.gravity[2]);
}

Eigen::Quaterniond FreeBodyAccelerometer::orientation(const mjData* d) const {
  const mjtNum* q = d->qpos + qpos_adr_ + 3;  // (w, x, y, z)
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized();
}

Eigen::Vector3d FreeBodyAccelerometer::site_position(const mjData* d) const {
  const mjtNum* p = d->qpos + qpos_adr_;
  return Eigen::Vector3d(p[0], p[1], p[2]) + orientation(d) * site_in_body_;
}

Eigen::Vector3d FreeBodyAccelerometer::site_velocity(const mjData* d) const {
  const mjtNum* v = d->qvel + dof_adr_;
  const Eigen::Vector3d linear(v[0], v[1], v[2]);
  const Eigen::Vector3d angular_body(v[3], v[4], v[5]);
  return linear + orientation(d) * angular_body.cross(site_in_body_);
}

void FreeBodyAccelerometer::before_step(const mjData* d) {
  position_before_ = site_position(d);
  orientation_before_ = orientation(d);
  if (!has_velocity_) {  // the first tick: the state's velocity stands for the last difference
    velocity_before_ = site_velocity(d);
    has_velocity_ = true;
  }
}

Eigen::Vector3d FreeBodyAccelerometer::after_step(const mjData* d) {
  const Eigen::Vector3d velocity_after = (site_position(d) - position_before_) / period_s_;
  const Eigen::Vector3d acceleration = (velocity_after - velocity_before_) / period_s_;
  velocity_before_ = velocity_after;
  const Eigen::Quaterniond site_orientation = orientation_before_ * site_orientation_in_body_;
  return site_orientation.conjugate() * (acceleration - gravity_);
}

}  // namespace ftsense::sim
