#include "core/pipeline/machine_context.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "core/diagnosis/gear_condition_indicators.h"
#include "core/inverse/identification_operator.h"

namespace gearpath {
namespace {

std::optional<Axis> ParseAxis(const std::string& s) {
  if (s == "x" || s == "X") return Axis::kX;
  if (s == "y" || s == "Y") return Axis::kY;
  if (s == "z" || s == "Z") return Axis::kZ;
  return std::nullopt;
}

const char* AxisName(Axis a) { return a == Axis::kX ? "x" : (a == Axis::kY ? "y" : "z"); }

}  // namespace

Result<MachineContext> MachineContext::Create(MachineSetup setup) {
  MachineContext mc;
  MachineContext* impl = &mc;
  const AnalysisOptions& o = setup.options;
  const FrfSet& set = setup.frf_set;
  const std::string& id = setup.machine_id;
  if (id.empty()) return Error{"machine setup: machine_id is empty"};
  const std::string at = "machine '" + id + "': ";
  if (!(o.sample_rate_hz > 0.0) || !std::isfinite(o.sample_rate_hz)) {
    return Error{at + fmt::format("options.sample_rate_hz must be > 0, got {}", o.sample_rate_hz)};
  }
  if (!(o.sample_rate_tolerance >= 0.0) || o.sample_rate_tolerance > 0.1) {
    return Error{at + "options.sample_rate_tolerance must be in [0, 0.1]"};
  }
  if (o.min_samples_per_channel < 64 || o.min_samples_per_channel > o.max_samples_per_channel) {
    return Error{at + fmt::format("options.min_samples_per_channel ({}) must be >= 64 and <= "
                                  "max_samples_per_channel ({})",
                                  o.min_samples_per_channel, o.max_samples_per_channel)};
  }
  if (!(o.nominal_speed_hz >= 0.0) || !std::isfinite(o.nominal_speed_hz)) {
    return Error{at + "options.nominal_speed_hz must be finite and >= 0"};
  }
  if (o.speed_search_lo_hz < 0.0 || o.speed_search_hi_hz < 0.0 ||
      (o.speed_search_hi_hz > 0.0 && o.speed_search_hi_hz <= o.speed_search_lo_hz)) {
    return Error{at + "options.speed_search_lo_hz/hi_hz must satisfy 0 <= lo < hi"};
  }
  if (o.sideband_orders < 1 || o.sideband_orders > 50) {
    return Error{at + "options.sideband_orders must be in 1..50"};
  }
  if (!(o.harmonic_tolerance >= 0.0) || o.harmonic_tolerance > 0.2) {
    return Error{at + "options.harmonic_tolerance must be in [0, 0.2]"};
  }
  if (!(o.false_alarm_rate > 0.0 && o.false_alarm_rate < 0.5)) {
    return Error{at + fmt::format("options.false_alarm_rate must be in (0, 0.5), got {}",
                                  o.false_alarm_rate)};
  }
  if (!(o.scale_floor >= 0.0 && o.scale_floor <= 1.0)) {
    return Error{at + fmt::format("options.scale_floor must be in [0, 1], got {}", o.scale_floor)};
  }
  if (!(o.speed_tolerance >= 0.0 && o.speed_tolerance <= 1.0)) {
    return Error{at + fmt::format("options.speed_tolerance must be in [0, 1], got {}",
                                  o.speed_tolerance)};
  }
  if (!(o.load_tolerance >= 0.0 && o.load_tolerance <= 1.0)) {
    return Error{at +
                 fmt::format("options.load_tolerance must be in [0, 1], got {}", o.load_tolerance)};
  }
  if (o.operating_bands < 1 || o.operating_bands > kMaxOperatingBands) {
    return Error{at + fmt::format("options.operating_bands must be in [1, {}], got {}",
                                  kMaxOperatingBands, o.operating_bands)};
  }
  if (Status st = ValidateBaselineEpoch(o.baseline_epoch); !st) {
    return Error{at + "options.baseline_epoch " + st.error()};
  }
  if (!(o.mesh_separation >= 1.0 && o.mesh_separation <= 100.0)) {
    return Error{
        at + fmt::format("options.mesh_separation must be in [1, 100], got {}", o.mesh_separation)};
  }
  if (auto st = ValidateIdentificationOptions(o.identification); !st) {
    return Error{at + "options.identification: " + st.error()};
  }
  const FrfMatrix& h = set.decoupled;
  if (h.bins() == 0 || h.at.empty()) {
    return Error{at + "frf_set has no decoupled FRF matrix (run `gearpath decouple` first)"};
  }
  if (static_cast<std::size_t>(h.outputs()) != set.channels.size() ||
      static_cast<std::size_t>(h.inputs()) != set.paths.size()) {
    return Error{at + fmt::format("frf_set.decoupled is {}x{} but the set lists {} channels and "
                                  "{} paths",
                                  h.outputs(), h.inputs(), set.channels.size(), set.paths.size())};
  }
  impl->channels = set.channels.size();
  impl->paths = set.paths.size();

  // Channel mapping: block channel c -> FRF row with the same (sensor, axis).
  std::vector<ExpectedChannel> frf_channels;
  for (std::size_t r = 0; r < set.channels.size(); ++r) {
    const auto axis = ParseAxis(set.channels[r].axis);
    if (!axis) {
      return Error{at + fmt::format("frf_set.channels[{}].axis '{}' is not x, y or z", r,
                                    set.channels[r].axis)};
    }
    frf_channels.push_back({set.channels[r].sensor, *axis});
  }
  if (setup.block_channels.empty()) setup.block_channels = frf_channels;
  if (setup.block_channels.size() != frf_channels.size()) {
    return Error{at + fmt::format("block_channels lists {} channels but the FRF set has {} rows",
                                  setup.block_channels.size(), frf_channels.size())};
  }
  std::vector<bool> row_used(frf_channels.size(), false);
  for (std::size_t c = 0; c < setup.block_channels.size(); ++c) {
    const ExpectedChannel& bc = setup.block_channels[c];
    int row = -1;
    for (std::size_t r = 0; r < frf_channels.size(); ++r) {
      if (frf_channels[r].sensor == bc.sensor && frf_channels[r].axis == bc.axis) {
        row = static_cast<int>(r);
      }
    }
    if (row < 0) {
      return Error{at + fmt::format("block_channels[{}] ({}/{}) has no row in the FRF set", c,
                                    bc.sensor, AxisName(bc.axis))};
    }
    if (row_used[static_cast<std::size_t>(row)]) {
      return Error{at + fmt::format("block_channels[{}] ({}/{}) is listed twice", c, bc.sensor,
                                    AxisName(bc.axis))};
    }
    row_used[static_cast<std::size_t>(row)] = true;
    impl->block_to_row.push_back(row);
  }
  if (o.indicator_channel >= static_cast<int>(impl->channels) || o.indicator_channel < -1) {
    return Error{at + fmt::format("options.indicator_channel {} is not an FRF row (0..{}) or -1",
                                  o.indicator_channel, impl->channels - 1)};
  }

  // Train kinematics and the verdict's topology.
  auto ratios = ShaftRateRatios(setup.train);
  if (!ratios) return Error{at + ratios.error()};
  impl->shaft_ratio = ratios.value();
  impl->max_ratio = *std::max_element(impl->shaft_ratio.begin(), impl->shaft_ratio.end());
  const TrainLayout& train = setup.train;
  VerdictTopology& t = impl->topology;
  t.rate_tolerance = std::max(o.harmonic_tolerance, 1e-6);
  for (const TrainShaft& s : train.shafts) t.shaft_names.push_back(s.name);
  t.shaft_ratio = impl->shaft_ratio;
  t.gear_mesh.assign(train.gears.size(), -1);
  for (const TrainGear& g : train.gears) {
    t.gear_names.push_back(g.name);
    t.gear_shaft.push_back(g.shaft);
  }
  if (train.meshes.size() > kMaxTrainMeshes) {
    return Error{at + "train has more than " + std::to_string(kMaxTrainMeshes) + " meshes"};
  }
  for (std::size_t m = 0; m < train.meshes.size(); ++m) {
    const TrainGear& a = train.gears[static_cast<std::size_t>(train.meshes[m].gear_a)];
    const TrainGear& b = train.gears[static_cast<std::size_t>(train.meshes[m].gear_b)];
    for (int gi : {train.meshes[m].gear_a, train.meshes[m].gear_b}) {
      if (t.gear_mesh[static_cast<std::size_t>(gi)] >= 0) {
        return Error{at + fmt::format("gear '{}' is in two meshes; the verdict needs one mesh per "
                                      "gear (an idler must be modelled as two gears)",
                                      train.gears[static_cast<std::size_t>(gi)].name)};
      }
      t.gear_mesh[static_cast<std::size_t>(gi)] = static_cast<int>(m);
    }
    t.mesh_names.push_back(a.name + "-" + b.name);
    MeshLines lines;
    lines.mesh_hz = a.teeth * impl->shaft_ratio[static_cast<std::size_t>(a.shaft)];
    lines.shaft_hz = {impl->shaft_ratio[static_cast<std::size_t>(a.shaft)],
                      impl->shaft_ratio[static_cast<std::size_t>(b.shaft)]};
    impl->unit_meshes.push_back(lines);
    impl->mesh_orders.push_back(lines.mesh_hz);
  }
  for (std::size_t p = 0; p < set.paths.size(); ++p) {
    std::vector<int> seen;
    for (const std::string& gear : set.paths[p].gears) {
      const auto it = std::find(t.gear_names.begin(), t.gear_names.end(), gear);
      if (it == t.gear_names.end()) {
        return Error{at + fmt::format("frf_set.paths[{}] ({}) names gear '{}', which is not in "
                                      "the gear train",
                                      p, set.paths[p].name, gear)};
      }
      const int mesh = t.gear_mesh[static_cast<std::size_t>(it - t.gear_names.begin())];
      if (mesh >= 0 && std::find(seen.begin(), seen.end(), mesh) == seen.end()) {
        seen.push_back(mesh);
      }
    }
    t.path_meshes.push_back(std::move(seen));
    t.path_names.push_back(set.paths[p].name);
  }

  // Speed bounds: the search range and the highest speed the envelope band must serve.
  double lo = o.speed_search_lo_hz;
  double hi = o.speed_search_hi_hz;
  if (hi <= 0.0) {
    lo = o.nominal_speed_hz > 0.0 ? 0.8 * o.nominal_speed_hz : 1.0;
    hi = o.nominal_speed_hz > 0.0 ? 1.2 * o.nominal_speed_hz : 100.0;
  }
  impl->setup.options.speed_search_lo_hz = lo;
  impl->setup.options.speed_search_hi_hz = hi;
  impl->max_speed_hz = std::max(hi, o.nominal_speed_hz);

  // Analysis band: the FRF range, narrowed by the options.
  impl->band_lo = std::max(o.analysis_band_lo_hz, h.frequency_hz[0]);
  impl->band_hi = o.analysis_band_hi_hz > 0.0
                      ? std::min(o.analysis_band_hi_hz, h.frequency_hz[h.bins() - 1])
                      : h.frequency_hz[h.bins() - 1];
  impl->band_hi = std::min(impl->band_hi, o.sample_rate_hz / 2.0);
  if (!(impl->band_hi > impl->band_lo)) {
    return Error{at + fmt::format("analysis band {}..{} Hz is empty inside the FRF range "
                                  "{}..{} Hz",
                                  o.analysis_band_lo_hz, o.analysis_band_hi_hz, h.frequency_hz[0],
                                  h.frequency_hz[h.bins() - 1])};
  }

  // Rate groups: shafts at the same rate share one synchronous average.
  const double tol = t.rate_tolerance;
  impl->shaft_group.assign(train.shafts.size(), -1);
  for (std::size_t s = 0; s < train.shafts.size(); ++s) {
    const double r = impl->shaft_ratio[s];
    int found = -1;
    for (std::size_t g = 0; g < impl->rate_groups.size(); ++g) {
      if (std::abs(impl->rate_groups[g].ratio - r) <= tol * r) found = static_cast<int>(g);
    }
    if (found < 0) {
      impl->rate_groups.push_back(RateGroup{r, {}, {}, {}, {}, {}, {}, {}, {}});
      found = static_cast<int>(impl->rate_groups.size()) - 1;
    }
    impl->rate_groups[static_cast<std::size_t>(found)].shafts.push_back(static_cast<int>(s));
    impl->shaft_group[s] = found;
  }
  for (std::size_t g = 0; g < train.gears.size(); ++g) {
    RateGroup& rg = impl->rate_groups[static_cast<std::size_t>(
        impl->shaft_group[static_cast<std::size_t>(train.gears[g].shaft)])];
    rg.gears.push_back(static_cast<int>(g));
    rg.gear_teeth.push_back(train.gears[g].teeth);
    rg.gear_meshes.push_back(t.gear_mesh[g]);
  }

  // Each group's distinct meshes and their orders on its synchronous average (a gear of z
  // teeth meshes at order z of its own shaft; both gears of a mesh may sit in one group).
  for (RateGroup& rg : impl->rate_groups) {
    for (std::size_t i = 0; i < rg.gears.size(); ++i) {
      const int mesh = rg.gear_meshes[i];
      if (mesh < 0 || std::find(rg.meshes.begin(), rg.meshes.end(), mesh) != rg.meshes.end()) {
        continue;
      }
      if (rg.meshes.size() >= kMaxMeshesPerShaft) {
        return Error{at + fmt::format("shafts at ratio {} carry more than {} meshes", rg.ratio,
                                      kMaxMeshesPerShaft)};
      }
      rg.meshes.push_back(mesh);
      rg.mesh_orders.push_back(rg.gear_teeth[i]);
    }
    for (std::size_t k = 0; k < kConditionIndicatorCount; ++k) {
      const auto indicator = static_cast<ConditionIndicator>(k);
      rg.indicator_names.emplace_back(ConditionIndicatorName(indicator));
      rg.indicator_powers.push_back(AmplitudePower(indicator));
    }
    for (int mesh : rg.meshes) {
      rg.indicator_names.push_back("sideband_" + t.mesh_names[static_cast<std::size_t>(mesh)]);
      rg.indicator_powers.push_back(2);  // an energy
    }
    rg.indicator_names.emplace_back("exclusive_residual");
    rg.indicator_powers.push_back(2);
  }

  // Condition-indicator signals and the indicator vector's layout.
  for (std::size_t r = 0; r < set.channels.size(); ++r) {
    impl->condition_signals.push_back({ConditionSource::kMeasured, static_cast<int>(r),
                                       set.channels[r].sensor + "/" + set.channels[r].axis});
  }
  for (std::size_t p = 0; p < set.paths.size(); ++p) {
    impl->condition_signals.push_back(
        {ConditionSource::kContribution, static_cast<int>(p), set.paths[p].name});
  }
  for (std::size_t p = 0; p < set.paths.size(); ++p) {
    impl->condition_signals.push_back(
        {ConditionSource::kForce, static_cast<int>(p), set.paths[p].name});
  }
  std::size_t offset = 0;
  for (std::size_t sig = 0; sig < impl->condition_signals.size(); ++sig) {
    for (std::size_t g = 0; g < impl->rate_groups.size(); ++g) {
      const std::size_t count = impl->rate_groups[g].indicator_names.size();
      impl->condition_slots.push_back({sig, g, offset, count});
      offset += count;
    }
  }
  impl->signature_offset = offset;
  for (std::size_t g = 0; g < impl->rate_groups.size(); ++g) {
    const RateGroup& rg = impl->rate_groups[g];
    for (bool forces : {false, true}) {
      for (std::size_t i = 0; i < rg.meshes.size(); ++i) {
        impl->signature_slots.push_back({g, forces, i, offset});
        const std::string tail = t.mesh_names[static_cast<std::size_t>(rg.meshes[i])] + "_" +
                                 (forces ? "forces" : "measured") + "@" +
                                 t.shaft_names[static_cast<std::size_t>(rg.shafts.front())];
        impl->signature_names.push_back("signature_parallel_" + tail);
        impl->signature_names.push_back("signature_orthogonal_" + tail);
        offset += 2;
      }
    }
  }
  impl->envelope_offset = offset;
  for (const char* kind : {"envelope_raw_", "envelope_rec_"}) {
    for (const TrainShaft& s : train.shafts) impl->envelope_names.push_back(kind + s.name);
  }
  impl->tracked_offset = offset + impl->envelope_names.size();
  offset = impl->tracked_offset + set.channels.size() * impl->rate_groups.size();
  for (SignatureSlot& ss : impl->signature_slots) {
    if (ss.forces) continue;
    ss.tracked_offset = offset;
    offset += 2 * static_cast<std::size_t>(kSignatureHarmonics);
  }
  impl->indicator_count = offset;
  // Only the measured channels' condition indicators are scored, not the forces' or the
  // contributions' (indicator_scoring_stage.h): the z limit counts what is scored.
  for (const ConditionSlot& cs : impl->condition_slots) {
    const ConditionSource source = impl->condition_signals[cs.signal].source;
    if (source == ConditionSource::kMeasured) impl->scored_indicator_count += cs.count;
  }
  for (const SignatureSlot& ss : impl->signature_slots) {
    if (!ss.forces) impl->scored_indicator_count += 2;
  }
  // The envelope indicators are published, not scored (indicator_scoring_stage.cc).

  impl->expect.machine_id = id;
  impl->expect.channels = setup.block_channels;
  impl->expect.sample_rate_hz = o.sample_rate_hz;
  impl->expect.sample_rate_tolerance = o.sample_rate_tolerance;
  impl->expect.min_samples_per_channel = o.min_samples_per_channel;
  impl->expect.max_samples_per_channel = o.max_samples_per_channel;
  impl->expect.max_total_samples =
      static_cast<std::size_t>(o.max_samples_per_channel) * impl->channels;
  // Plausible speed of a block: a factor 2 around the speed range the analysis is set up for
  // (the search range, +/-20 % around nominal by default; the envelope band is sized for its
  // top). Wider than any drift of a fixed-speed machine, narrower than the usual publisher
  // errors (rpm sent as Hz: x60; rad/s: x6.3) and than garbage such as 1e300.
  constexpr double kSpeedPlausibleFactor = 2.0;
  impl->expect.min_speed_hz = lo / kSpeedPlausibleFactor;
  impl->expect.max_speed_hz = kSpeedPlausibleFactor * impl->max_speed_hz;

  const double keep_lo = impl->setup.options.speed_search_lo_hz;
  const double keep_hi = impl->setup.options.speed_search_hi_hz;
  impl->setup = std::move(setup);
  impl->setup.options.speed_search_lo_hz = keep_lo;
  impl->setup.options.speed_search_hi_hz = keep_hi;
  impl->expect.machine_id = impl->setup.machine_id;
  return mc;
}

}  // namespace gearpath
