// Scenario matrix of the evaluation: which plant, train, fault, gear, speed, noise, channel set
// and disturbances each scenario runs, and its seed.
//
// Dimensions: family (plant_family.h) x train variant (table1, distinct) x fault kind (none,
// te_pulse, mesh_am, wear_dip, combined) x faulty gear (G1..G4; healthy scenarios run
// kHealthyReplicas replicas instead, so there are as many healthy as faulty scenarios per
// fault kind) x input speed (200, 300, 450, 600, 900 r/min: 300..600 is the nominal band,
// 200 and 900 lie outside it) x noise (2, 5, 10 %) x channel set (p1..p3; p1..p3 + m1) x
// unmodelled sources (off; on = pump tones + random bursts + +/- 0.3 % speed drift).
//
//  full   the whole factorial.
//  quick  every (family, variant, fault, gear or replica) cell once, with the nuisance
//         dimensions (speed, noise, channel set, unmodelled) ROTATED over the cells (a
//         Latin-square-like design: each level appears about equally often), so every level
//         of every dimension is exercised in a few hundred scenarios.
// Seeds are derived from the scenario's identity (its key string, FNV-1a then SplitMix64),
// not its position, so a scenario has the same seed in the quick and the full matrix, and
// filtering families does not change any other scenario.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/evaluation/plant_excitation.h"
#include "core/evaluation/plant_family.h"

namespace gearpath {

inline constexpr int kHealthyReplicas = 4;
inline constexpr double kMatrixSpeedsRpm[] = {200.0, 300.0, 450.0, 600.0, 900.0};
inline constexpr double kMatrixNoise[] = {0.02, 0.05, 0.10};
inline constexpr double kNominalBandLoRpm = 300.0;
inline constexpr double kNominalBandHiRpm = 600.0;

struct Scenario {
  std::size_t index = 0;  // position in the enumerated list
  PlantFamily family = PlantFamily::kLumpedPerturbed;
  TrainVariant variant = TrainVariant::kTable1;
  PlantFaultKind fault = PlantFaultKind::kNone;
  std::string gear;  // faulty gear name; empty for kNone
  int replica = 0;   // healthy replica (0 for faults)
  double input_rpm = 600.0;
  double noise = 0.05;
  ChannelSet channels = ChannelSet::kSeats;
  bool unmodelled = false;
  std::uint64_t seed = 0;

  // e.g. "lumped_perturbed/table1/te_pulse/G1/600rpm/n5/p/clean"
  std::string Key() const;
  bool held_out() const { return IsHeldOut(family); }
};

// "below" (< 300 r/min), "nominal" (300..600), "above" (> 600).
std::string_view SpeedBand(double input_rpm) noexcept;

enum class MatrixSize : std::uint8_t { kQuick, kFull };
std::optional<MatrixSize> ParseMatrixSize(std::string_view name) noexcept;

enum class HeldOutSelection : std::uint8_t { kInclude, kExclude, kOnly };

struct MatrixFilter {
  std::vector<PlantFamily> families;  // empty = all
  HeldOutSelection held_out = HeldOutSelection::kExclude;
  std::string key_contains;  // only scenarios whose key contains this text; empty = all
};

std::vector<Scenario> EnumerateScenarios(MatrixSize size, const MatrixFilter& filter = {});

// A random subset of n scenarios that is the same in every run: the n with the smallest seeds
// (a seed is a hash of the key, so this is a uniform draw, independent of the order), kept in
// their original order and re-indexed 0..n-1. Why: the full matrix costs ~40 minutes and the
// quick one's 64 faulty scenarios leave a ~5-point standard error; a few hundred drawn from the
// full factorial sit between. n >= scenarios.size() returns them all.
std::vector<Scenario> SampleScenarios(std::vector<Scenario> scenarios, std::size_t n);

std::uint64_t ScenarioSeed(std::string_view key) noexcept;

}  // namespace gearpath
