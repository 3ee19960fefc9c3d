// Per-axis peaks of the gimbal drives over a run: winding current, mean voltage over a step, torque at the
// axis. Allocation-free; fed per plant step by the drives (sim/plants/power_stabilizer_plant.hpp).
#pragma once

#include <cmath>
#include <cstddef>

namespace gyrostab::analysis {

struct DrivePeaks {
  double current_A[2]{0.0, 0.0};
  double voltage_V[2]{0.0, 0.0};
  double torque_Nm[2]{0.0, 0.0};
  void add(std::size_t axis, double i, double u, double tq) {
    current_A[axis] = std::fmax(current_A[axis], std::fabs(i));
    voltage_V[axis] = std::fmax(voltage_V[axis], std::fabs(u));
    torque_Nm[axis] = std::fmax(torque_Nm[axis], std::fabs(tq));
  }
};

}  // namespace gyrostab::analysis
