// The directional gyro's correction loops as the closed loop runs them (docs/sampled-data.md): the instrument
// of sim/models/directional_gyro.hpp (exact gimbal kinematics) linearised at the plant's current state on its
// current case rate (straight and level flight: the Earth's and the transport rate) by central differences of
// its own derivative; the firmware's corrections (firmware/control/directional_gyro_corrections.hpp:
// compensation, heading correction, inter-gimbal correction) probed at the gyro's indication, their limit
// lifted; sampled with the zero-order hold at the law's period and the latency
// (sim/analysis/sampled_loop_roots.hpp). The inter-gimbal correction's mode is the real root nearest −k/H of
// (12.24) β' = −(k/H) β; at the scenes' rates the sampling moves it by (k/H) T (L + ½) ≈ 4e-4 relative.
#pragma once

#include <complex>

#include "sim/analysis/sampled_loop_roots.hpp"
#include "sim/plants/directional_gyro_plant.hpp"
#include "tools/devices/directional_gyro/directional_gyro_scene.hpp"

namespace gyrostab::tools {

struct DirectionalGyroSampled {
  double continuous{0.0};  // the linearised loop's inter-gimbal root [1/s]
  std::complex<double> sampled{0.0, 0.0};  // the sampled loop's root nearest it [1/s]
  analysis::SampledLoopRoots roots;
};
// At the plant's state and case rate now (a straight, level segment), with ψ_soll held at the true heading.
DirectionalGyroSampled directional_gyro_sampled(const DirectionalGyroScene& s, const plants::DirectionalGyroPlant& p);

}  // namespace gyrostab::tools
