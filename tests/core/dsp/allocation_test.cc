// The per-block process steps of core/dsp allocate nothing once configured (DESIGN.md: hot
// paths allocate nothing). Checked by counting global operator new calls while they run; the
// replacement operators (tests/core/counting_operator_new.h) are included here, once for this
// test executable, and count only inside a scope.
#include <gtest/gtest.h>

#include <complex>
#include <cstdlib>
#include <new>
#include <vector>

#include "core/dsp/band_pass.h"
#include "core/dsp/envelope.h"
#include "core/dsp/envelope_spectrum.h"
#include "core/dsp/harmonic_indicator.h"
#include "core/dsp/kurtogram.h"
#include "core/dsp/order_tracker.h"
#include "core/dsp/spectrum.h"
#include "tests/core/counting_operator_new.h"
#include "tests/core/dsp/test_signals.h"

namespace {
thread_local bool counting = false;
thread_local int allocations = 0;
}  // namespace

void counting_new::OnAllocation() noexcept {
  if (counting) ++allocations;
}

namespace gearpath {
namespace {

class AllocationCounter {
 public:
  AllocationCounter() {
    allocations = 0;
    counting = true;
  }
  ~AllocationCounter() { counting = false; }
  int count() const { return allocations; }
};

constexpr double kFs = 8000.0;
constexpr std::size_t kN = 4096;

TEST(DspAllocations, ProcessStepsAllocateNothingOnceConfigured) {
  std::vector<double> x = dsp_test::WhiteNoise(2 * kN, 1.0, 9);
  dsp_test::AddResonanceImpulses(x, kFs, 20.0, 0.01, 2000.0, 0.03, 3.0);
  const std::span<const double> one(x.data(), kN);

  auto spectrum = Spectrum::Create(kN, 2, kFs).value();
  auto inverse = InverseSpectrum::Create(kN, 2).value();
  auto kurtogram = Kurtogram::Create(kN, kFs, KurtogramOptions{}).value();
  auto band_pass = BandPass::Create(kN, kFs, 50.0).value();
  auto envelope = Envelope::Create(kN).value();
  auto ses = EnvelopeSpectrum::Create(kN, kFs).value();
  std::vector<std::complex<double>> s(2 * spectrum.bin_count());
  std::vector<std::complex<double>> z(kN);
  std::vector<double> y(2 * kN);
  std::vector<double> e(ses.bin_count());

  // Each step runs once before counting: a first call may warm lazily built state elsewhere.
  auto allocations_of = [](auto&& step) {
    EXPECT_TRUE(step());
    AllocationCounter counter;
    const bool ok = step();
    const int count = counter.count();
    EXPECT_TRUE(ok);
    return count;
  };
  EXPECT_EQ(allocations_of([&] { return spectrum.Process(x, s).ok(); }), 0);
  EXPECT_EQ(allocations_of([&] { return inverse.Process(s, y).ok(); }), 0);
  KurtogramBand band;
  EXPECT_EQ(allocations_of([&] {
              auto r = kurtogram.Process(one);
              if (r.ok()) band = *r;
              return r.ok();
            }),
            0);
  EXPECT_EQ(allocations_of([&] {
              return band_pass.Process(one, band.low_hz, band.high_hz, std::span(y).first(kN)).ok();
            }),
            0);
  EXPECT_EQ(allocations_of([&] { return envelope.ProcessAnalytic(one, z).ok(); }), 0);
  EXPECT_EQ(allocations_of([&] { return ses.Process(std::span(y).first(kN), e).ok(); }), 0);
  EXPECT_EQ(allocations_of([&] { return ComputeHarmonicIndicator(e, ses.bin_hz(), 20.0).ok(); }),
            0);
  EXPECT_EQ(allocations_of([&] { return EnhancementPercent(2.0, 1.0).ok(); }), 0);
}

// The condition stage tries several tracking carriers in every block and expects some to fail:
// TryTrack() allocates nothing, tracked or not (Track() builds its failure's message).
TEST(DspAllocations, TryTrackAllocatesNothingWhetherItTracksOrNot) {
  std::vector<double> tone(kN);
  for (std::size_t i = 0; i < kN; ++i) {
    tone[i] = std::cos(2.0 * 3.141592653589793 * 300.0 * static_cast<double>(i) / kFs);
  }
  const std::vector<double> noise = dsp_test::WhiteNoise(kN, 1.0, 3);
  auto tracker = OrderTracker::Create(kN, kFs).value();
  std::vector<double> warp(kN);
  const auto allocations_of = [&](const std::vector<double>& x, double carrier_hz, bool tracks) {
    EXPECT_EQ(tracker.TryTrack(x, carrier_hz, 6.0, warp).has_value(), tracks);
    AllocationCounter counter;
    const bool tracked = tracker.TryTrack(x, carrier_hz, 6.0, warp).has_value();
    const int count = counter.count();
    EXPECT_EQ(tracked, tracks);
    return count;
  };
  EXPECT_EQ(allocations_of(tone, 300.0, true), 0);
  EXPECT_EQ(allocations_of(noise, 300.0, false), 0);    // no carrier
  EXPECT_EQ(allocations_of(tone, 3999.0, false), 0);    // band outside (0, fs / 2)
  EXPECT_FALSE(tracker.Track(noise, 300.0, 6.0, warp).ok());  // Track() still says why
}

}  // namespace
}  // namespace gearpath
