#include "daemon/machine_setup_builder.h"

#include <fmt/format.h>

#include <vector>

#include "core/frf/identity_frf_set.h"
#include "core/io/frf_set_io.h"
#include "daemon/frf_registry.h"

namespace gearpath::daemon {
namespace {

using nlohmann::json;

Axis AxisFromName(const std::string& name) {
  if (name == "y") return Axis::kY;
  if (name == "z") return Axis::kZ;
  return Axis::kX;  // the schema admits only x, y, z
}

std::string Names(const std::vector<TransferPath>& paths) {
  std::string out;
  for (const auto& p : paths) out += (out.empty() ? "" : ", ") + p.name;
  return out;
}

template <typename T>
T Get(const json& j, const char* key) {
  return j.at(key).get<T>();
}

AnalysisOptions TranslateOptions(const json& m) {
  AnalysisOptions o;
  const json& a = m.at("analysis");
  const json& inv = a.at("inverse");
  const auto method = Get<std::string>(inv, "method");
  o.identification.method = method == "tikhonov"        ? InverseMethod::kTikhonov
                            : method == "least_squares" ? InverseMethod::kLeastSquares
                                                        : InverseMethod::kMwi;
  const auto rule = Get<std::string>(inv, "alpha_rule");
  auto& reg = o.identification.regularisation;
  reg.rule = rule == "fixed"         ? RegularisationRule::kFixed
             : rule == "discrepancy" ? RegularisationRule::kDiscrepancy
             : rule == "gcv"         ? RegularisationRule::kGcv
                                     : RegularisationRule::kNoiseFloor;
  reg.parameter = Get<double>(inv, "alpha");
  reg.relative_noise = Get<double>(inv, "relative_noise");
  reg.noise_rms = Get<double>(inv, "noise_rms");
  reg.discrepancy_factor = Get<double>(inv, "discrepancy_factor");
  o.identification.iterations = Get<int>(inv, "iterations");

  const json& acq = m.at("acquisition");
  o.sample_rate_hz = Get<double>(acq, "sample_rate_hz");
  o.sample_rate_tolerance = Get<double>(acq, "sample_rate_tolerance");
  o.min_samples_per_channel = Get<std::uint32_t>(acq, "min_samples_per_channel");
  o.max_samples_per_channel = Get<std::uint32_t>(acq, "max_samples_per_channel");

  o.nominal_speed_hz = Get<double>(m, "nominal_speed_hz");
  o.speed_search_lo_hz = Get<double>(a.at("speed"), "search_lo_hz");
  o.speed_search_hi_hz = Get<double>(a.at("speed"), "search_hi_hz");
  o.order_tracking = Get<bool>(a.at("speed"), "order_tracking");
  o.localisation_tracking = Get<bool>(a.at("speed"), "localisation_tracking");
  o.transient_gate = Get<bool>(a.at("condition"), "transient_gate");

  const json& dom = a.at("dominant_path");
  const auto criterion = Get<std::string>(dom, "criterion");
  o.criterion = criterion == "band_energy" ? AnalysisOptions::DominantCriterion::kBandEnergy
                : criterion == "indicator" ? AnalysisOptions::DominantCriterion::kIndicator
                                           : AnalysisOptions::DominantCriterion::kSidebandEnergy;
  o.analysis_band_lo_hz = Get<double>(dom, "band_lo_hz");
  o.analysis_band_hi_hz = Get<double>(dom, "band_hi_hz");
  o.sideband_orders = Get<int>(dom, "sideband_orders");
  o.indicator_channel = Get<int>(dom, "indicator_channel");

  const json& env = a.at("envelope");
  o.kurtogram_max_level = Get<int>(env, "kurtogram_max_level");
  o.min_band_width_hz = Get<double>(env, "min_band_width_hz");
  o.remove_mesh_tones = Get<bool>(env, "remove_mesh_tones");
  o.harmonic_tolerance = Get<double>(env, "harmonic_tolerance");

  const json& base = a.at("baseline");
  o.baseline_blocks = Get<int>(base, "learning_blocks");
  o.baseline_k_sigma = Get<double>(base, "k_sigma");
  o.false_alarm_rate = Get<double>(base, "false_alarm_rate");
  o.scale_floor = Get<double>(base, "scale_floor");
  o.tail_guard = Get<bool>(base, "tail_guard");
  o.speed_tolerance = Get<double>(base, "speed_tolerance");
  o.load_tolerance = Get<double>(base, "load_tolerance");
  o.operating_bands = Get<int>(base, "operating_bands");
  o.baseline_epoch = Get<std::string>(base, "epoch");
  const json& alarm = a.at("alarm");
  o.alarm_window = Get<int>(alarm, "window");
  o.suspect_k = Get<int>(alarm, "suspect_blocks");
  o.alarm_k = Get<int>(alarm, "alarm_blocks");
  o.clear_level = Get<double>(alarm, "clear_level");
  o.clear_blocks = Get<int>(alarm, "clear_blocks");
  o.mesh_separation = Get<double>(alarm, "mesh_separation");
  o.raw_thresholds = Get<std::vector<double>>(base, "raw_thresholds");
  o.reconstructed_thresholds = Get<std::vector<double>>(base, "reconstructed_thresholds");
  return o;
}

// The validated gear_train object (names already cross-checked by daemon_config) as a layout.
TrainLayout TranslateTrain(const json& train) {
  TrainLayout layout;
  const json& shafts = train.at("shafts");
  for (const auto& s : shafts) layout.shafts.push_back({Get<std::string>(s, "name")});
  auto shaft_of = [&](const std::string& gear) {
    for (std::size_t i = 0; i < shafts.size(); ++i) {
      for (const auto& g : shafts[i].at("gears")) {
        if (g.get<std::string>() == gear) return static_cast<int>(i);
      }
    }
    return -1;
  };
  for (const auto& g : train.at("gears")) {
    const auto name = Get<std::string>(g, "name");
    layout.gears.push_back({name, Get<int>(g, "teeth"), shaft_of(name)});
  }
  auto gear_index = [&](const std::string& name) {
    for (std::size_t i = 0; i < layout.gears.size(); ++i) {
      if (layout.gears[i].name == name) return static_cast<int>(i);
    }
    return -1;
  };
  for (const auto& stage : train.at("stages")) {
    layout.meshes.push_back({gear_index(Get<std::string>(stage, "driver")),
                             gear_index(Get<std::string>(stage, "driven"))});
  }
  layout.input_shaft = 0;
  return layout;
}

}  // namespace

Result<FrfSet> LoadFrfSource(const std::string& source, const std::string& key_path) {
  if (source.starts_with(kBuiltinPrefix)) {
    auto set = BuiltinFrfSet(source.substr(kBuiltinPrefix.size()));
    if (!set) return Error{fmt::format("{}: {}: {}", key_path, source, set.error())};
    return set;
  }
  auto set = ReadFrfSet(source);
  if (!set) return Error{fmt::format("{}: {}", key_path, set.error())};
  if (set->decoupled.bins() == 0) {
    return Error{fmt::format("{}: {}: the set has no decoupled FRF matrix (run `gearpath "
                             "decouple` on it first)",
                             key_path, source)};
  }
  return set;
}

Result<FrfSet> IdentityFrfSetFor(const MachineConfig& machine) {
  const json& m = machine.settings;
  const std::string& at = machine.key_path;
  std::vector<ResponseChannel> channels;
  std::vector<std::vector<std::string>> gears;
  for (const json& c : m.at("channels")) {
    channels.push_back({Get<std::string>(c, "sensor"), Get<std::string>(c, "axis")});
    gears.push_back(c.contains("gears") ? Get<std::vector<std::string>>(c, "gears")
                                        : std::vector<std::string>{});
  }
  const json& acq = m.at("acquisition");
  const double fs = Get<double>(acq, "sample_rate_hz");
  const auto n_min = Get<long>(acq, "min_samples_per_channel");
  const auto n_max = Get<long>(acq, "max_samples_per_channel");
  std::vector<double> grid;
  if (n_max > n_min) grid.push_back(fs / static_cast<double>(n_max));
  for (long k = 1; 2 * k <= n_min; ++k) {
    grid.push_back(fs * static_cast<double>(k) / static_cast<double>(n_min));
  }
  if (grid.back() < fs / 2.0) grid.push_back(fs / 2.0);
  const Eigen::VectorXd frequency_hz =
      Eigen::Map<const Eigen::VectorXd>(grid.data(), static_cast<Eigen::Index>(grid.size()));
  auto set = MakeIdentityFrfSet(channels, gears, frequency_hz);
  if (!set) {
    // Config-level rules (daemon_config.cc) catch these first; name the key all the same.
    return Error{fmt::format("{}.channels: identity FRF set: {}", at, set.error())};
  }
  return set;
}

Result<MachineSetup> BuildMachineSetup(const MachineConfig& machine, FrfRegistry* registry) {
  const json& m = machine.settings;
  const std::string& at = machine.key_path;
  MachineSetup setup;
  setup.machine_id = machine.id;
  if (registry != nullptr) {
    auto shared = registry->Get(machine);
    if (!shared) return Error{shared.error()};
    setup.frf_set = *shared->names;
    // A copy for BlockProcessor::Create to validate, dropped there for the shared one.
    setup.frf_set.decoupled = shared->operators->decoupled();
    setup.shared_frf = shared->operators;
  } else {
    const bool identity = machine.frf_set == kIdentityFrfSet;
    auto set =
        identity ? IdentityFrfSetFor(machine) : LoadFrfSource(machine.frf_set, at + ".frf_set");
    if (!set) return Error{set.error()};
    setup.frf_set = std::move(set.value());
  }
  FrfSet& frf = setup.frf_set;

  const json& channels = m.at("channels");
  for (std::size_t i = 0; i < channels.size(); ++i) {
    const auto sensor = Get<std::string>(channels[i], "sensor");
    const auto axis = Get<std::string>(channels[i], "axis");
    const long row = Get<long>(channels[i], "frf_row");
    if (row >= 0) {
      if (static_cast<std::size_t>(row) >= frf.channels.size()) {
        return Error{fmt::format("{}.channels[{}].frf_row: row {} is out of range (the FRF set "
                                 "has {} response channels)",
                                 at, i, row, frf.channels.size())};
      }
      frf.channels[static_cast<std::size_t>(row)] = {sensor, axis};
    }
    setup.block_channels.push_back({sensor, AxisFromName(axis)});
  }

  const json& paths = m.at("paths");
  for (std::size_t i = 0; i < paths.size(); ++i) {
    const auto name = Get<std::string>(paths[i], "name");
    TransferPath* path = nullptr;
    for (auto& p : frf.paths) path = p.name == name ? &p : path;
    if (path == nullptr) {
      return Error{fmt::format("{}.paths[{}].name: the FRF set has no path \"{}\" (its paths: "
                               "{})",
                               at, i, name, Names(frf.paths))};
    }
    path->gears = Get<std::vector<std::string>>(paths[i], "gears");
  }

  setup.train = TranslateTrain(m.at("gear_train"));
  if (auto ratios = ShaftRateRatios(setup.train); !ratios) {
    return Error{fmt::format("{}.gear_train: {}", at, ratios.error())};
  }
  setup.options = TranslateOptions(m);
  return setup;
}

}  // namespace gearpath::daemon
