#include "core/pipeline/learned_state.h"

#include <fmt/format.h>
#include <xxhash.h>

#include <complex>
#include <string_view>

#include "core/dsp/order_tracker.h"
#include "core/pipeline/machine_context.h"

namespace gearpath {
namespace {

// 64-bit FNV-1a: a fingerprint against accidental mismatch, not an authenticator.
class Fnv1a {
 public:
  void Bytes(const void* data, std::size_t size) noexcept {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) {
      hash_ ^= p[i];
      hash_ *= 0x100000001b3ULL;
    }
  }
  void Text(std::string_view s) noexcept {
    Number(static_cast<double>(s.size()));  // length first: "ab"+"c" differs from "a"+"bc"
    Bytes(s.data(), s.size());
  }
  void Number(double v) noexcept {
    if (v == 0.0) v = 0.0;  // -0 and +0 configure the same thing
    Bytes(&v, sizeof v);
  }
  std::uint64_t value() const noexcept { return hash_; }

 private:
  std::uint64_t hash_ = 0xcbf29ce484222325ULL;
};

}  // namespace

Status ValidateBaselineEpoch(std::string_view epoch) {
  for (std::size_t i = 0; i < epoch.size(); ++i) {
    const auto c = static_cast<unsigned char>(epoch[i]);
    if (c < 0x20 || c == 0x7f) {
      return Error{
          fmt::format("holds control character 0x{:02x} at byte {}: give one line of "
                      "printable text",
                      c, i)};
    }
  }
  if (epoch.size() > kMaxBaselineEpochBytes) {
    return Error{fmt::format("is {} bytes long, at most {}", epoch.size(), kMaxBaselineEpochBytes)};
  }
  return Status::Ok();
}

namespace {

// How the FRF matrix, the bulk of what is fingerprinted (18 MB at the reference workload), goes
// into the hash.
enum class FrfBytes {
  // Every byte through FNV-1a (version 1): one dependent multiply per byte, ~25 ms per
  // processor at the reference workload, paid at every start and reload of every machine.
  kEveryByte,
  // Each bin's bytes digested by XXH3 (xxhash, Debian's libxxhash) and the digest through
  // FNV-1a (version 2): ~1 ms.
  kDigestPerBin,
};

std::uint64_t Fingerprint(const MachineContext& m, FrfBytes frf_bytes) {
  Fnv1a h;
  h.Text(frf_bytes == FrfBytes::kEveryByte ? "gearpath learned state v1"
                                           : "gearpath learned state v2");
  const FrfSet& set = m.setup.frf_set;
  const FrfMatrix& frf = set.decoupled;
  h.Number(static_cast<double>(frf.bins()));
  h.Bytes(frf.frequency_hz.data(), sizeof(double) * static_cast<std::size_t>(frf.bins()));
  for (const auto& bin : frf.at) {
    const std::size_t bytes = sizeof(std::complex<double>) * static_cast<std::size_t>(bin.size());
    if (frf_bytes == FrfBytes::kEveryByte) {
      h.Bytes(bin.data(), bytes);
    } else {
      const std::uint64_t digest = XXH3_64bits(bin.data(), bytes);
      h.Bytes(&digest, sizeof digest);
    }
  }
  for (const auto& p : set.paths) h.Text(p.name);
  for (const auto& c : set.channels) {
    h.Text(c.sensor);
    h.Text(c.axis);
  }
  for (int row : m.block_to_row) h.Number(row);
  const TrainLayout& t = m.setup.train;
  for (const auto& s : t.shafts) h.Text(s.name);
  for (const auto& g : t.gears) {
    h.Text(g.name);
    h.Number(g.teeth);
    h.Number(g.shaft);
  }
  for (const auto& mesh : t.meshes) {
    h.Number(mesh.gear_a);
    h.Number(mesh.gear_b);
  }
  h.Number(t.input_shaft);
  // The indicator layout, name by name.
  h.Number(static_cast<double>(m.indicator_count));
  for (const auto& g : m.rate_groups) {
    for (const auto& name : g.indicator_names) h.Text(name);
  }
  for (const auto& name : m.envelope_names) h.Text(name);
  // The options that change indicator values (not the false-alarm rate, the alarm model or
  // the mesh decision: they judge the indicators, the baseline does not depend on them).
  const AnalysisOptions& o = m.setup.options;
  const IdentificationOptions& id = o.identification;
  h.Number(static_cast<double>(id.method));
  h.Number(static_cast<double>(id.regularisation.rule));
  h.Number(id.regularisation.parameter);
  h.Number(id.regularisation.relative_noise);
  h.Number(id.regularisation.noise_rms);
  h.Number(id.regularisation.discrepancy_factor);
  h.Number(id.iterations);
  h.Number(id.rank_tolerance);
  h.Number(o.sample_rate_hz);
  h.Number(o.nominal_speed_hz);
  h.Number(o.speed_search_lo_hz);
  h.Number(o.speed_search_hi_hz);
  h.Number(o.order_tracking ? 1 : 0);
  h.Number(o.localisation_tracking ? 1 : 0);
  // The tracker's warps (and with them the tracked averages) changed with its revision; the
  // warp median of the condition stage came with revision 2.
  if (o.order_tracking || o.localisation_tracking) h.Number(kOrderTrackerRevision);
  // Only when on: a state learned before the gate existed (or with it off) measured the same.
  if (o.transient_gate) h.Text("transient gate 1");
  h.Number(static_cast<double>(o.criterion));
  h.Number(o.criterion_over_baseline ? 1 : 0);
  h.Number(m.band_lo);
  h.Number(m.band_hi);
  h.Number(o.sideband_orders);
  h.Number(o.indicator_channel);
  h.Number(o.kurtogram_max_level);
  h.Number(o.min_band_width_hz);
  h.Number(o.remove_mesh_tones ? 1 : 0);
  h.Number(o.harmonic_tolerance);
  for (double v : o.raw_thresholds) h.Number(v);
  for (double v : o.reconstructed_thresholds) h.Number(v);
  h.Number(o.baseline_blocks);
  h.Number(o.baseline_k_sigma);
  h.Number(o.scale_floor);
  h.Number(o.tail_guard ? 1 : 0);
  // Only when set: a state saved without an epoch measured the same.
  if (!o.baseline_epoch.empty()) {
    h.Text("baseline epoch");
    h.Text(o.baseline_epoch);
  }
  return h.value();
}

}  // namespace

std::uint64_t LearnedStateFingerprint(const MachineContext& m) {
  return Fingerprint(m, FrfBytes::kDigestPerBin);
}

std::uint64_t LegacyLearnedStateFingerprint(const MachineContext& m) {
  return Fingerprint(m, FrfBytes::kEveryByte);
}

}  // namespace gearpath
