#include "core/evaluation/scenario_matrix.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/simulation/deterministic_rng.h"

namespace gearpath {
namespace {

constexpr const char* kGears[] = {"G1", "G2", "G3", "G4"};

bool FamilySelected(PlantFamily family, const MatrixFilter& filter) {
  if (!filter.families.empty() &&
      std::find(filter.families.begin(), filter.families.end(), family) == filter.families.end()) {
    return false;
  }
  switch (filter.held_out) {
    case HeldOutSelection::kInclude:
      return true;
    case HeldOutSelection::kExclude:
      return !IsHeldOut(family);
    case HeldOutSelection::kOnly:
      return IsHeldOut(family);
  }
  return false;
}

// The (fault, gear-or-replica) cells of one family and variant.
struct Cell {
  PlantFaultKind fault;
  std::string gear;
  int replica;
};

std::vector<Cell> Cells() {
  std::vector<Cell> cells;
  for (PlantFaultKind kind : kAllPlantFaultKinds) {
    if (kind == PlantFaultKind::kNone) {
      for (int r = 0; r < kHealthyReplicas; ++r) cells.push_back({kind, "", r});
    } else {
      for (const char* g : kGears) cells.push_back({kind, g, 0});
    }
  }
  return cells;
}

}  // namespace

std::string Scenario::Key() const {
  return fmt::format("{}/{}/{}/{}/{}rpm/n{}/{}/{}", PlantFamilyName(family),
                     TrainVariantName(variant), PlantFaultKindName(fault),
                     fault == PlantFaultKind::kNone ? fmt::format("r{}", replica) : gear,
                     std::lround(input_rpm), std::lround(noise * 100.0), ChannelSetName(channels),
                     unmodelled ? "disturbed" : "clean");
}

std::string_view SpeedBand(double input_rpm) noexcept {
  if (input_rpm < kNominalBandLoRpm - 1e-9) return "below";
  if (input_rpm > kNominalBandHiRpm + 1e-9) return "above";
  return "nominal";
}

std::optional<MatrixSize> ParseMatrixSize(std::string_view name) noexcept {
  if (name == "quick") return MatrixSize::kQuick;
  if (name == "full") return MatrixSize::kFull;
  return std::nullopt;
}

std::uint64_t ScenarioSeed(std::string_view key) noexcept {
  std::uint64_t h = 0xcbf29ce484222325ull;  // FNV-1a
  for (char c : key) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001b3ull;
  }
  return SplitMix64(h);
}

std::vector<Scenario> EnumerateScenarios(MatrixSize size, const MatrixFilter& filter) {
  std::vector<Scenario> out;
  const std::vector<Cell> cells = Cells();
  auto push = [&out, &filter](Scenario s) {
    if (!filter.key_contains.empty() &&
        s.Key().find(filter.key_contains) == std::string::npos) {
      return;
    }
    s.index = out.size();
    s.seed = ScenarioSeed(s.Key());
    out.push_back(std::move(s));
  };
  for (PlantFamily family : kAllPlantFamilies) {
    if (!FamilySelected(family, filter)) continue;
    const std::size_t f = static_cast<std::size_t>(family);
    for (TrainVariant variant : {TrainVariant::kTable1, TrainVariant::kDistinct}) {
      const std::size_t v = static_cast<std::size_t>(variant);
      for (const Cell& cell : cells) {
        Scenario base;
        base.family = family;
        base.variant = variant;
        base.fault = cell.fault;
        base.gear = cell.gear;
        base.replica = cell.replica;
        if (size == MatrixSize::kQuick) {
          // Rotate the nuisance levels over slot j (gear or replica), kind k, variant and
          // family, with different strides, so that every level of every dimension appears
          // about equally often, healthy and faulty alike, and no two dimensions move together.
          const std::size_t j = static_cast<std::size_t>(
              cell.fault == PlantFaultKind::kNone ? cell.replica : cell.gear[1] - '1');
          const std::size_t k = static_cast<std::size_t>(cell.fault);
          base.input_rpm = kMatrixSpeedsRpm[(j + k + 2 * v + f) % 5];
          base.noise = kMatrixNoise[(j + 2 * k + v + f) % 3];
          base.channels = (j + k + v) % 2 == 0 ? ChannelSet::kSeats : ChannelSet::kSeatsAndHousing;
          base.unmodelled = (j / 2 + k + v + f) % 2 == 1;
          push(base);
          continue;
        }
        for (double rpm : kMatrixSpeedsRpm) {
          for (double noise : kMatrixNoise) {
            for (ChannelSet ch : {ChannelSet::kSeats, ChannelSet::kSeatsAndHousing}) {
              for (bool unmodelled : {false, true}) {
                Scenario s = base;
                s.input_rpm = rpm;
                s.noise = noise;
                s.channels = ch;
                s.unmodelled = unmodelled;
                push(s);
              }
            }
          }
        }
      }
    }
  }
  return out;
}

std::vector<Scenario> SampleScenarios(std::vector<Scenario> scenarios, std::size_t n) {
  if (n >= scenarios.size()) return scenarios;
  std::vector<Scenario> by_seed = scenarios;
  std::nth_element(by_seed.begin(), by_seed.begin() + static_cast<std::ptrdiff_t>(n), by_seed.end(),
                   [](const Scenario& a, const Scenario& b) { return a.seed < b.seed; });
  const std::uint64_t cut = by_seed[n].seed;  // the (n+1)-th smallest seed
  std::vector<Scenario> out;
  out.reserve(n);
  for (Scenario& s : scenarios) {
    if (s.seed < cut && out.size() < n) {
      s.index = out.size();
      out.push_back(std::move(s));
    }
  }
  return out;
}

}  // namespace gearpath
