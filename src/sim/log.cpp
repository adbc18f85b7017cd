#include "sim/log.hpp"

#include <charconv>

namespace mospec::sim {

CsvLog::CsvLog(const World& world) : state_(world.make_state()) {
  std::string h = "t";
  for (const robot::ArmShape& arm : world.shape().arms) {
    const char* a = arm.name.c_str();
    for (const char* field : {"q", "qd", "tau"}) {
      for (int i = 0; i < arm.joints; ++i) {
        h += ",";
        h += a;
        h += "_";
        h += field;
        h += std::to_string(i);
      }
    }
  }
  for (int i = 0; i < world.shape().drives; ++i) h += ",pivot_q" + std::to_string(i);
  for (int i = 0; i < 2 * world.shape().drives; ++i) h += ",wheel_qd" + std::to_string(i);
  h += ",base_x,base_y,base_z,base_yaw";
  for (const robot::ArmShape& arm : world.shape().arms) {
    const std::string p = "," + arm.name + "_";
    h += p + "ee_x" + p + "ee_y" + p + "ee_z" + p + "fn" + p + "fx" + p + "fy" + p + "fz" + p +
         "mount_fx" + p + "mount_fy" + p + "mount_fz";
  }
  h += ",ground_fx,ground_fy,ground_mz\n";
  text_ = std::move(h);
}

void CsvLog::add(double x) {
  char buf[32];
  buf[0] = ',';
  if (x == 0.0) x = 0.0;  // no "-0"
  auto [end, ec] = std::to_chars(buf + 1, buf + sizeof buf, x);
  (void)ec;
  text_.append(buf, end);
}

void CsvLog::record(const World& world) {
  world.read_true(state_);
  const std::size_t start = text_.size();
  add(state_.clock.t);
  text_.erase(start, 1);  // no comma before the first column
  for (const robot::ArmMeasurement& a : state_.arm) {
    for (double x : a.q) add(x);
    for (double x : a.qd) add(x);
    for (double x : a.tau) add(x);
  }
  for (double x : state_.pivot_q) add(x);
  for (double x : state_.wheel_qd) add(x);
  for (double x : state_.truth.p_WoPo_W) add(x);
  add(state_.truth.yaw);
  for (size_t arm = 0; arm < state_.arm.size(); ++arm) {
    const int k = static_cast<int>(arm);
    const runtime::Vec3 p = world.p_WoE_W(k);
    const ArmContact c = world.contact(k);
    add(p.x());
    add(p.y());
    add(p.z());
    add(c.normal_force);
    add(c.f_E_W.x());
    add(c.f_E_W.y());
    add(c.f_E_W.z());
    add(c.f_mount_W.x());
    add(c.f_mount_W.y());
    add(c.f_mount_W.z());
  }
  const runtime::Vec3 w = world.ground_wrench_P();
  add(w.x());
  add(w.y());
  add(w.z());
  text_ += '\n';
  ++rows_;
}

}  // namespace mospec::sim
