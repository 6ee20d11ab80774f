#include "core/pipeline/shared_frf_operators.h"

#include <utility>

namespace gearpath {
namespace {

// Every field that changes the operator. The size check makes a new option field fail the
// build here rather than let two machines with different options share an operator.
static_assert(sizeof(IdentificationOptions) == 64,
              "IdentificationOptions changed: compare the new field in SameOptions");
bool SameOptions(const IdentificationOptions& a, const IdentificationOptions& b) noexcept {
  const RegularisationSettings& ra = a.regularisation;
  const RegularisationSettings& rb = b.regularisation;
  return a.method == b.method && a.iterations == b.iterations &&
         a.rank_tolerance == b.rank_tolerance && ra.rule == rb.rule &&
         ra.parameter == rb.parameter && ra.relative_noise == rb.relative_noise &&
         ra.noise_rms == rb.noise_rms && ra.discrepancy_factor == rb.discrepancy_factor;
}

}  // namespace

SharedFrfOperators::SharedFrfOperators(std::shared_ptr<const FrfMatrix> decoupled)
    : decoupled_(std::move(decoupled)) {}

Result<FrfGridMapping> SharedFrfOperators::Mapping(std::size_t block_length,
                                                   double sample_rate_hz) {
  MappingEntry* entry = nullptr;
  {
    std::lock_guard lock(mutex_);
    for (MappingEntry& e : mappings_) {
      if (e.block_length == block_length && e.sample_rate_hz == sample_rate_hz) entry = &e;
    }
    if (entry == nullptr) {
      entry = &mappings_.emplace_back();
      entry->block_length = block_length;
      entry->sample_rate_hz = sample_rate_hz;
    }
  }
  std::call_once(entry->once, [&] {
    entry->built.emplace(MapFrfToBlockGrid(*decoupled_, block_length, sample_rate_hz));
    std::lock_guard lock(mutex_);
    ++mappings_built_;
  });
  return *entry->built;  // a copy shares the mapped matrices
}

Result<IdentificationOperator> SharedFrfOperators::Operator(std::size_t block_length,
                                                            double sample_rate_hz,
                                                            const IdentificationOptions& options) {
  OperatorEntry* entry = nullptr;
  {
    std::lock_guard lock(mutex_);
    for (OperatorEntry& e : operators_) {
      if (e.block_length == block_length && e.sample_rate_hz == sample_rate_hz &&
          SameOptions(e.options, options)) {
        entry = &e;
      }
    }
    if (entry == nullptr) {
      entry = &operators_.emplace_back();
      entry->block_length = block_length;
      entry->sample_rate_hz = sample_rate_hz;
      entry->options = options;
    }
  }
  std::call_once(entry->once, [&] {
    auto map = Mapping(block_length, sample_rate_hz);
    if (!map) {
      entry->built.emplace(Error{map.error()});
      return;
    }
    entry->built.emplace(IdentificationOperator::Create(*map->in_range, options));
    std::lock_guard lock(mutex_);
    ++operators_built_;
  });
  return *entry->built;  // a copy shares the per-bin factorisations, not the workspace
}

Result<std::shared_ptr<const FrfPowerTable>> SharedFrfOperators::Power(std::size_t block_length,
                                                                       double sample_rate_hz) {
  PowerEntry* entry = nullptr;
  {
    std::lock_guard lock(mutex_);
    for (PowerEntry& e : powers_) {
      if (e.block_length == block_length && e.sample_rate_hz == sample_rate_hz) entry = &e;
    }
    if (entry == nullptr) {
      entry = &powers_.emplace_back();
      entry->block_length = block_length;
      entry->sample_rate_hz = sample_rate_hz;
    }
  }
  std::call_once(entry->once, [&] {
    auto map = Mapping(block_length, sample_rate_hz);
    if (!map) {
      entry->built.emplace(Error{map.error()});
      return;
    }
    entry->built.emplace(std::make_shared<const FrfPowerTable>(FrfPowerTable::Build(*map)));
    std::lock_guard lock(mutex_);
    ++power_tables_built_;
  });
  return *entry->built;  // the one table, shared
}

std::uint64_t SharedFrfOperators::mappings_built() const {
  std::lock_guard lock(mutex_);
  return mappings_built_;
}

std::uint64_t SharedFrfOperators::operators_built() const {
  std::lock_guard lock(mutex_);
  return operators_built_;
}

std::uint64_t SharedFrfOperators::power_tables_built() const {
  std::lock_guard lock(mutex_);
  return power_tables_built_;
}

bool SameFrfMatrix(const FrfMatrix& a, const FrfMatrix& b) noexcept {
  if (a.frequency_hz.size() != b.frequency_hz.size() || a.at.size() != b.at.size() ||
      a.frequency_hz != b.frequency_hz) {
    return false;
  }
  for (std::size_t k = 0; k < a.at.size(); ++k) {
    if (a.at[k].rows() != b.at[k].rows() || a.at[k].cols() != b.at[k].cols() ||
        a.at[k] != b.at[k]) {
      return false;
    }
  }
  return true;
}

Status DropOwnDecoupledCopy(MachineSetup& setup) {
  if (!setup.shared_frf) return Status::Ok();
  if (!SameFrfMatrix(setup.frf_set.decoupled, setup.shared_frf->decoupled())) {
    return Error{"machine '" + setup.machine_id +
                 "': the shared FRF operators were built from another decoupled FRF matrix"};
  }
  setup.frf_set.decoupled = FrfMatrix{};
  return Status::Ok();
}

}  // namespace gearpath
