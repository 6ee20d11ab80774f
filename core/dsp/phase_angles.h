// PhaseAngles: the angle of every value of a complex signal, arg(z) = atan2(im, re), in
// (-pi, pi], many at a time.
//
// Why. The order tracker takes the phase of a carrier's complex envelope at every sample of a
// block (16 000 per iteration and carrier at the reference shape); one std::arg per sample
// was a quarter of a Track(). With glibc's vector math library (libmvec, glibc >= 2.35 on
// x86-64, found by core/dsp/CMakeLists.txt) four (AVX2) or two values go through one call,
// each within 4 ulp of atan2 (glibc's bound for its vector functions; the scalar atan2 is
// itself not correctly rounded since glibc 2.35, and its result depends on the CPU's FMA too).
// Elsewhere it is std::arg per value.
#pragma once

#include <complex>
#include <span>

namespace gearpath {

// angle[i] = arg(z[i]) for i < min(z.size(), angle.size()).
void PhaseAngles(std::span<const std::complex<double>> z, std::span<double> angle) noexcept;

}  // namespace gearpath
