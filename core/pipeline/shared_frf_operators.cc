#include "core/pipeline/shared_frf_operators.h"

#include <list>
#include <mutex>
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

// The entry of `list` that `matches`, added (and set up by `init`) when there is none. The
// list is guarded by `mutex`; its entries stay put while others are added.
template <typename Entry, typename Match, typename Init>
Entry& FindOrAdd(std::mutex& mutex, std::list<Entry>& list, Match matches, Init init) {
  std::lock_guard lock(mutex);
  for (Entry& e : list) {
    if (matches(e)) return e;
  }
  Entry& e = list.emplace_back();
  init(e);
  return e;
}

// Builds entry.built once, never under `mutex` (later callers of the entry wait for the first);
// counts it in `built` when it succeeded.
template <typename Entry, typename Make>
void BuildOnce(Entry& entry, std::mutex& mutex, std::uint64_t& built, Make make) {
  std::call_once(entry.once, [&] {
    entry.built.emplace(make());
    if (!entry.built->ok()) return;
    std::lock_guard lock(mutex);
    ++built;
  });
}

}  // namespace

SharedFrfOperators::SharedFrfOperators(std::shared_ptr<const FrfMatrix> decoupled)
    : decoupled_(std::move(decoupled)) {}

Result<FrfGridMapping> SharedFrfOperators::Mapping(std::size_t block_length,
                                                   double sample_rate_hz) {
  MappingEntry& entry = FindOrAdd(
      mutex_, mappings_,
      [&](const MappingEntry& e) {
        return e.block_length == block_length && e.sample_rate_hz == sample_rate_hz;
      },
      [&](MappingEntry& e) {
        e.block_length = block_length;
        e.sample_rate_hz = sample_rate_hz;
      });
  BuildOnce(entry, mutex_, mappings_built_,
            [&] { return MapFrfToBlockGrid(*decoupled_, block_length, sample_rate_hz); });
  return *entry.built;  // a copy shares the mapped matrices
}

Result<IdentificationOperator> SharedFrfOperators::Operator(std::size_t block_length,
                                                            double sample_rate_hz,
                                                            const IdentificationOptions& options) {
  OperatorEntry& entry = FindOrAdd(
      mutex_, operators_,
      [&](const OperatorEntry& e) {
        return e.block_length == block_length && e.sample_rate_hz == sample_rate_hz &&
               SameOptions(e.options, options);
      },
      [&](OperatorEntry& e) {
        e.block_length = block_length;
        e.sample_rate_hz = sample_rate_hz;
        e.options = options;
      });
  BuildOnce(entry, mutex_, operators_built_, [&]() -> Result<IdentificationOperator> {
    auto map = Mapping(block_length, sample_rate_hz);
    if (!map) return Error{map.error()};
    return IdentificationOperator::Create(*map->in_range, options);
  });
  return *entry.built;  // a copy shares the per-bin factorisations, not the workspace
}

Result<std::shared_ptr<const FrfPowerTable>> SharedFrfOperators::Power(std::size_t block_length,
                                                                       double sample_rate_hz) {
  PowerEntry& entry = FindOrAdd(
      mutex_, powers_,
      [&](const PowerEntry& e) {
        return e.block_length == block_length && e.sample_rate_hz == sample_rate_hz;
      },
      [&](PowerEntry& e) {
        e.block_length = block_length;
        e.sample_rate_hz = sample_rate_hz;
      });
  BuildOnce(entry, mutex_, power_tables_built_,
            [&]() -> Result<std::shared_ptr<const FrfPowerTable>> {
              auto map = Mapping(block_length, sample_rate_hz);
              if (!map) return Error{map.error()};
              return std::make_shared<const FrfPowerTable>(FrfPowerTable::Build(*map));
            });
  return *entry.built;  // the one table, shared
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
