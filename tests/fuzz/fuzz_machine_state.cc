// libFuzzer target: a machine's saved state file (daemon/machine_state_store.h, docs/state.md),
// read as gearpathd reads it at a start, imported into a learned machine and, when accepted,
// judged on one block. The file is on disk and outlives the build that wrote it, so a bad one
// must be refused by name, never read out of bounds: an accepted state whose arrays disagree
// with the machine would show here as ASan's report in Process().
//
// The machine is small (identity FRFs, two channels, 1024-sample blocks) so that a judged input
// costs little. With GEARPATH_FUZZ_WRITE_SEED=<file> the target writes the learned machine's
// state there and exits: the seeds in tests/fuzz/corpus/fuzz_machine_state were made so
// (half_learned.state.json with GEARPATH_FUZZ_SEED_BLOCKS=2).
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>

#include "core/common/accel_block.h"
#include "core/pipeline/block_processor.h"
#include "daemon/daemon_config.h"
#include "daemon/machine_setup_builder.h"
#include "daemon/machine_state_store.h"
#include "tests/fuzz/machine_state_machine.h"

namespace {

namespace fs = std::filesystem;
using namespace gearpath;

constexpr char kMachineId[] = "fuzz";
constexpr double kSampleRateHz = 2048.0;
constexpr std::size_t kSamples = 1024;
constexpr double kInputHz = 10.0;

struct Harness {
  fs::path dir;
  std::optional<daemon::MachineStateStore> store;
  std::optional<BlockProcessor> processor;
  AccelBlock block;
  BlockResult result;
  std::uint64_t sequence = 1;
};

Harness* harness = nullptr;

// Two mesh tones and a little deterministic noise per channel: enough for every stage to run.
void FillBlock(AccelBlock& b, std::uint64_t sequence) {
  b.machine_id = kMachineId;
  b.sequence = sequence;
  b.sample_rate_hz = kSampleRateHz;
  b.speed_hz = kInputHz;
  b.speed_source = SpeedSource::kAcquisition;
  b.channels = {{"A1", Axis::kX, "m/s^2", 1.0}, {"A2", Axis::kZ, "m/s^2", 1.0}};
  b.samples_per_channel = kSamples;
  b.samples.assign(2 * kSamples, 0.0f);
  std::uint32_t noise = static_cast<std::uint32_t>(sequence) * 2654435761u + 1u;
  for (std::size_t c = 0; c < 2; ++c) {
    for (std::size_t i = 0; i < kSamples; ++i) {
      const double t = static_cast<double>(i) / kSampleRateHz;
      noise = noise * 1664525u + 1013904223u;
      const double n = (static_cast<double>(noise >> 8) / 16777216.0 - 0.5) * 0.05;
      b.samples[c * kSamples + i] = static_cast<float>(
          std::sin(2.0 * M_PI * 28.0 * kInputHz * t) +
          0.5 * std::sin(2.0 * M_PI * 34.0 * kInputHz * 28.0 / 40.0 * t + c) + n);
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  harness = new Harness;
  harness->dir = fs::temp_directory_path() / ("gearpath_fuzz_state_" + std::to_string(::getpid()));
  fs::remove_all(harness->dir);
  auto config = daemon::ParseDaemonConfig(kMachineStateConfig, "fuzz");
  if (!config.ok()) return 1;
  auto setup = daemon::BuildMachineSetup(config->machines.front());
  if (!setup.ok()) return 1;
  auto processor = BlockProcessor::Create(std::move(setup.value()));
  if (!processor.ok()) return 1;
  harness->processor.emplace(std::move(processor.value()));
  auto store = daemon::MachineStateStore::Open(harness->dir.string());
  if (!store.ok()) return 1;
  harness->store.emplace(std::move(store.value()));
  // Learned and past it, so that a seed state is one a judging machine saved (or as many blocks
  // as GEARPATH_FUZZ_SEED_BLOCKS says: 2 leaves the baseline half learned, its samples kept).
  const char* seed_blocks = std::getenv("GEARPATH_FUZZ_SEED_BLOCKS");
  const int blocks = seed_blocks ? std::atoi(seed_blocks) : 4;
  for (int i = 0; i < blocks; ++i) {
    FillBlock(harness->block, harness->sequence);
    if (!harness->processor->Process(harness->block.view(), harness->result).accepted()) return 1;
    ++harness->sequence;
  }
  if (const char* seed = std::getenv("GEARPATH_FUZZ_WRITE_SEED")) {
    daemon::SavedMachine saved;
    saved.machine_id = kMachineId;
    saved.saved_at_ns = 1795000000000000000;
    saved.learned = harness->processor->ExportLearnedState();
    if (!harness->store->Save(saved).ok()) return 1;
    fs::copy_file(harness->store->PathOf(kMachineId), seed, fs::copy_options::overwrite_existing);
    std::exit(0);
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Harness& h = *harness;
  {
    std::ofstream out(h.store->PathOf(kMachineId), std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  auto saved = h.store->Load(kMachineId);
  if (!saved.ok() || !saved.value()) return 0;
  if (!h.processor->ImportLearnedState(saved.value()->learned).ok()) return 0;
  // Accepted: the machine must judge with it, and save it again.
  FillBlock(h.block, h.sequence++);
  (void)h.processor->Process(h.block.view(), h.result);
  (void)h.processor->ExportLearnedState();
  return 0;
}
