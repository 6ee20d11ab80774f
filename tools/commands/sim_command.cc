// `gearpath sim`: simulate the seed's Table 1 gearbox (lumped model, core/model) running at
// constant speed, healthy or with one gear fault (core/simulation), offline: prints the
// kinematics (seed Table 6), the synthesis period and per-channel levels of the generated
// blocks, and optionally writes the machine's FRF set (--write-frf-set, docs/frf_format.md) on
// the block length's bin grid, so the daemon can diagnose the simulated machine.
// With --publish it feeds a running daemon instead: the blocks go out on the DDS block topic
// (loopback configuration), paced in real time, N times faster, or as fast as the daemon takes
// them. --healthy-blocks N puts N healthy blocks first, so the daemon learns its healthy
// baseline before the fault appears, as it would on a real machine.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/io/frf_set_io.h"
#include "core/model/gear_train.h"
#include "core/model/lumped_gearbox_model.h"
#include "core/simulation/fault_excitation.h"
#include "core/simulation/gearbox_simulator.h"
#include "core/simulation/model_frf_set.h"
#include "tools/commands/commands.h"
#include "tools/common/block_publisher.h"
#include "tools/common/cli_checks.h"

namespace gearpath::tools {
namespace {

struct SimOptions {
  std::string fault = "none";
  std::string gear;
  double severity = 1.0;
  double speed_rpm = 600.0;
  // 5 % like a real acquisition: a noise-free healthy baseline has a zero spread, against
  // which a noisy plant looks faulty and a small fault looks like nothing in particular.
  double noise = 0.05;
  std::uint64_t seed = 1;
  double sample_rate = 8000.0;
  std::uint32_t block_length = 8192;
  std::uint32_t blocks = 4;
  std::uint32_t healthy_blocks = 0;      // healthy blocks before the fault starts
  bool housing_channel = false;          // append the central housing point m1 to p1..p3
  std::string machine_id = "table1";     // the daemon's embedded default machine
  bool publish = false;
  int domain_id = 0;
  DdsOptions dds;
  double speedup = 1.0;                  // 1 = real time; --fast sets 0 (as fast as taken)
  bool fast = false;
  std::string frf_set_dir;
  std::string frf_decoupling = "eq22";
  bool with_coupled = false;
  // > 0: every block carries this load reading (published as AccelBlockV2 in load_unit).
  double load = 0.0;
  std::string load_unit = "N m";
};

int RunSim(const SimOptions& o) {
  const auto bad = [](const std::string& why) {
    std::fprintf(stderr, "gearpath sim: %s\n", why.c_str());
    return kExitBadInput;
  };
  const std::optional<FaultType> type = ParseFaultType(o.fault);
  if (!type) return bad("--fault must be none, chipped, wear or fracture, got \"" + o.fault + "\"");
  if (*type != FaultType::kNone && o.gear.empty()) {
    return bad("--fault " + o.fault + " needs --gear (G1..G4)");
  }
  static const std::map<std::string, ModelFrfDecoupling> kDecoupling = {
      {"eq22", ModelFrfDecoupling::kVirtualEq22},
      {"eq24", ModelFrfDecoupling::kVirtualEq24},
      {"physical-pp", ModelFrfDecoupling::kPhysicalPp},
      {"physical-mp", ModelFrfDecoupling::kPhysicalMp}};
  const auto decoupling = kDecoupling.find(o.frf_decoupling);
  if (decoupling == kDecoupling.end()) {
    return bad("--frf-decoupling must be eq22, eq24, physical-pp or physical-mp, got \"" +
               o.frf_decoupling + "\"");
  }

  Result<LumpedGearboxModel> model = LumpedGearboxModel::Create(Table1Parameters());
  if (!model.ok()) {
    std::fprintf(stderr, "gearpath sim: %s\n", model.error().c_str());
    return kExitFailure;
  }
  const GearTrain train = GearTrain::Table1();
  SimulatorConfig config;
  config.machine_id = o.machine_id;
  config.fault = {*type, o.gear, o.severity};
  config.input_speed_hz = RpmToHz(o.speed_rpm);
  config.sample_rate_hz = o.sample_rate;
  config.block_length = o.block_length;
  config.noise_relative = o.noise;
  config.seed = o.seed;
  config.include_housing_channel = o.housing_channel;
  config.start_time_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                             std::chrono::system_clock::now().time_since_epoch())
                             .count();
  // One continuous stream: healthy blocks first (when asked), then the faulty ones, with
  // sequence numbers and t0 running on across the switch.
  std::optional<GearboxSimulator> healthy;
  if (o.healthy_blocks > 0 && *type != FaultType::kNone) {
    SimulatorConfig hc = config;
    hc.fault = {FaultType::kNone, "", 0.0};
    Result<GearboxSimulator> h = GearboxSimulator::Create(*model, train, hc);
    if (!h.ok()) return bad(h.error());
    healthy.emplace(std::move(*h));
    config.first_sequence = o.healthy_blocks;
    config.start_time_ns += static_cast<std::int64_t>(
        std::llround(1e9 * o.healthy_blocks * o.block_length / o.sample_rate));
  }
  Result<GearboxSimulator> sim = GearboxSimulator::Create(*model, train, config);
  if (!sim.ok()) return bad(sim.error());

  const Result<TrainKinematics> kin = train.Kinematics(sim->speed_hz());
  if (!kin.ok()) return bad(kin.error());
  std::printf("input speed %.6g r/min (%.6g Hz)%s\n", HzToRpm(sim->speed_hz()), sim->speed_hz(),
              std::abs(sim->speed_hz() - config.input_speed_hz) > 0.0
                  ? " (snapped so the common period is a whole number of samples)"
                  : "");
  for (const ShaftKinematics& s : kin->shafts) {
    std::printf("  shaft %-14s %9.4f Hz\n", s.name.c_str(), s.rotation_hz);
  }
  for (std::size_t m = 0; m < kin->meshes.size(); ++m) {
    const MeshKinematics& mk = kin->meshes[m];
    std::printf("  mesh %zu (%s-%s)     %9.4f Hz, contact ratio %.3f\n", m + 1, mk.driver.c_str(),
                mk.driven.c_str(), mk.mesh_hz, mk.contact_ratio);
  }
  if (*type == FaultType::kNone) {
    std::printf("fault: none (healthy)\n");
  } else {
    const GearKinematics& g = kin->gears[static_cast<std::size_t>(train.GearIndex(o.gear))];
    std::printf(
        "fault: %s on %s (shaft %s, mesh %d), characteristic frequency %.4f Hz, "
        "severity %g, pulse %.3g um over %.3g ms\n",
        FaultTypeName(*type), g.name.c_str(),
        train.shafts[static_cast<std::size_t>(g.shaft)].name.c_str(), g.stage + 1,
        g.characteristic_hz, o.severity, sim->excitation().fault_depth_m() * 1e6,
        sim->excitation().fault_length_s() * 1e3);
  }
  std::printf("synthesis period %zu samples (%.6g s) at %g Hz\n", sim->period_samples(),
              static_cast<double>(sim->period_samples()) / o.sample_rate, o.sample_rate);

  std::optional<BlockPublisher> publisher;
  if (o.publish) {
    PublisherOptions po;
    po.domain_id = o.domain_id;
    po.dds = o.dds;
    po.speedup = o.fast ? 0.0 : o.speedup;
    if (o.load > 0.0) po.load_unit = o.load_unit;
    try {
      publisher.emplace(po);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "gearpath sim: %s\n", e.what());
      return kExitFailure;
    }
    std::printf("publishing %u blocks of machine '%s' on DDS domain %d (%s)%s\n", o.blocks,
                o.machine_id.c_str(), o.domain_id,
                o.fast ? "as fast as taken" : (std::to_string(o.speedup) + " x real time").c_str(),
                healthy ? (", fault from block " + std::to_string(o.healthy_blocks)).c_str()
                        : "");
    std::fflush(stdout);
  }

  AccelBlock block;
  std::vector<double> sum2(sim->channels().size(), 0.0);
  for (std::uint32_t b = 0; b < o.blocks; ++b) {
    (healthy && b < o.healthy_blocks ? *healthy : *sim).NextBlock(block);
    block.load = o.load;
    if (publisher) {
      if (Status st = publisher->Publish(block.view()); !st) {
        std::fprintf(stderr, "gearpath sim: %s\n", st.error().c_str());
        return kExitFailure;
      }
    }
    for (std::size_t c = 0; c < block.channels.size(); ++c) {
      for (std::uint32_t i = 0; i < block.samples_per_channel; ++i) {
        const double v = block.samples[c * block.samples_per_channel + i];
        sum2[c] += v * v;
      }
    }
  }
  if (publisher) {
    // Reliable delivery: do not exit (and tear the writer down) before the daemon has them.
    if (Status st = publisher->Flush(std::chrono::seconds(30)); !st) {
      std::fprintf(stderr, "gearpath sim: %s\n", st.error().c_str());
      return kExitFailure;
    }
  }
  if (o.blocks > 0) {
    std::printf("%u blocks of %u samples, noise %g x RMS; RMS per channel (m/s^2):\n", o.blocks,
                o.block_length, o.noise);
    for (std::size_t c = 0; c < sum2.size(); ++c) {
      std::printf("  %-3s %.6g\n", sim->channels()[c].sensor.c_str(),
                  std::sqrt(sum2[c] / (static_cast<double>(o.blocks) * o.block_length)));
    }
  }

  if (!o.frf_set_dir.empty()) {
    // The bins of one block (0 Hz excluded: the accelerance vanishes there).
    const Eigen::Index bins = static_cast<Eigen::Index>(o.block_length / 2);
    if (bins < 1) return bad("--block-length must be >= 2 to write an FRF set");
    Eigen::VectorXd freq(bins);
    for (Eigen::Index k = 0; k < bins; ++k) {
      freq(k) = static_cast<double>(k + 1) * o.sample_rate / o.block_length;
    }
    ModelFrfSetOptions fo;
    fo.decoupling = decoupling->second;
    fo.include_coupled = o.with_coupled;
    fo.description = "gearpath sim: lumped model of the seed's Table 1 gearbox";
    Result<FrfSet> set = MakeModelFrfSet(*model, train, freq, fo);
    if (!set.ok()) return bad(set.error());
    if (Status st = WriteFrfSet(*set, o.frf_set_dir); !st) {
      std::fprintf(stderr, "gearpath sim: %s\n", st.error().c_str());
      return kExitFailure;
    }
    std::printf("wrote FRF set (%s, %lld bins, %zu channels x %zu paths) to %s\n",
                set->decoupling.c_str(), static_cast<long long>(bins), set->channels.size(),
                set->paths.size(), o.frf_set_dir.c_str());
  }
  return kExitOk;
}

}  // namespace

void AddSimCommand(CLI::App& app, int& exit_code) {
  auto opt = std::make_shared<SimOptions>();
  CLI::App* cmd = app.add_subcommand(
      "sim",
      "Simulate the Table 1 gearbox (healthy or one gear fault): summarise it, write its FRF "
      "set, or publish its blocks to a running gearpathd (--publish)");
  cmd->add_option("--fault", opt->fault, "none, chipped, wear or fracture")->capture_default_str();
  cmd->add_option("--gear", opt->gear, "faulty gear: G1, G2, G3 or G4");
  cmd->add_option("--severity", opt->severity, "fault depth scale (1 = the seed's damage)")
      ->capture_default_str()
      ->check(NonNegative());
  cmd->add_option("--speed-rpm", opt->speed_rpm, "input-shaft speed, r/min")
      ->capture_default_str()
      ->check(Positive());
  cmd->add_option("--noise", opt->noise, "measurement noise std / noise-free RMS per channel (0: none)")
      ->capture_default_str()
      ->check(NonNegative());
  cmd->add_option("--seed", opt->seed, "seed of phases, damaged tooth and noise")
      ->capture_default_str();
  cmd->add_option("--sample-rate", opt->sample_rate, "Hz")
      ->capture_default_str()
      ->check(Positive());
  cmd->add_option("--block-length", opt->block_length, "samples per channel and block")
      ->capture_default_str()
      ->check(Positive());
  cmd->add_option("--blocks", opt->blocks, "number of blocks to generate")->capture_default_str();
  cmd->add_option("--machine-id", opt->machine_id, "machine id of the blocks")
      ->capture_default_str();
  cmd->add_option("--healthy-blocks", opt->healthy_blocks,
                  "healthy blocks before the fault starts (for the daemon's baseline)")
      ->capture_default_str();
  cmd->add_flag("--housing-channel", opt->housing_channel,
                "also output the central housing point m1 (an Eq. 24 FRF set needs it)");
  cmd->add_flag("--publish", opt->publish,
                "publish the blocks on the DDS block topic (loopback configuration)");
  cmd->add_option("--domain", opt->domain_id, "DDS domain id, with --publish")
      ->capture_default_str()
      ->check(CLI::Range(0, 232));
  AddDdsOptions(cmd, &opt->dds);
  cmd->add_option("--speed", opt->speedup, "with --publish: pace at N x real time")
      ->capture_default_str()
      ->check(Positive());
  cmd->add_flag("--fast", opt->fast,
                "with --publish: as fast as the daemon takes them (nothing is lost)");
  cmd->add_option("--load", opt->load,
                  "with --publish: every block carries this load reading, on the AccelBlockV2 "
                  "topic (the simulated response does not depend on it)")
      ->check(CLI::Range(0.0, 1e12));
  cmd->add_option("--load-unit", opt->load_unit, "unit of --load (at most 16 characters)")
      ->capture_default_str();
  cmd->add_option("--write-frf-set", opt->frf_set_dir,
                  "write the machine's FRF set (on the block's bin grid) to this directory");
  cmd->add_option("--frf-decoupling", opt->frf_decoupling,
                  "eq22 (seats, Eq. 22), eq24 (housing point, Eq. 24), physical-pp, physical-mp")
      ->capture_default_str();
  cmd->add_flag("--with-coupled", opt->with_coupled,
                "also store the coupled blocks (a, p, m) in the FRF set");
  cmd->callback([opt, &exit_code] { exit_code = RunSim(*opt); });
}

}  // namespace gearpath::tools
