// Speed estimate by mesh-frequency tracking: the input-shaft speed that puts the most spectral
// power on the gear-mesh harmonics, used when neither the block nor the configuration gives
// the speed (or to check a configured one).
//
// Mesh m turns at f_mesh,m = o_m f_in with o_m = z_driver * (driver shaft rate / input rate)
// (o = 28 for Table 1's first mesh, 23.8 for its second). The score of a candidate f_in is
//   S(f) = sum_m sum_{h=1..H} A(h o_m f),
// A(f) the amplitude spectrum linearly interpolated between bins. Mesh tones are the strongest
// deterministic lines of a gearbox, so S peaks at the true speed; several meshes and harmonics
// make the peak sharp (each line moves h o_m times faster than f_in) and suppress subharmonic
// aliases. The search grid steps so that the highest line moves a quarter bin per step, then a
// parabola through the best three points refines it. The result carries the peak-to-mean ratio
// of S over the search range: close to 1 means there were no mesh lines to track.
#pragma once

#include <span>

namespace gearpath {

struct SpeedSearch {
  double lo_hz = 0.0;  // input-speed search range, 0 < lo < hi
  double hi_hz = 0.0;
  int harmonics = 3;            // H
  double min_prominence = 3.0;  // peak / mean score below this -> not found
};

struct SpeedEstimate {
  double speed_hz = 0.0;
  double prominence = 0.0;  // S(peak) / mean S over the range
  bool found = false;
};

// amplitude: one-sided amplitude spectrum (bin k at k bin_hz); mesh_orders: o_m per mesh.
// noexcept, allocation-free. Invalid arguments give found = false.
SpeedEstimate EstimateSpeedFromMeshes(std::span<const double> amplitude, double bin_hz,
                                      std::span<const double> mesh_orders,
                                      const SpeedSearch& search) noexcept;

}  // namespace gearpath
