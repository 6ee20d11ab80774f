// SharedFrfOperators: one decoupled FRF matrix and what is precomputed from it per block shape
// (its grid mapping, its identification operator and its |H|^2 table), built once and shared
// read-only by every BlockProcessor that is handed it (MachineSetup::shared_frf). A plant with a
// hundred gearboxes of one type holds one FRF set and one set of per-bin operators instead of a
// hundred.
//
// Entries are keyed by block length, sample rate and identification options: machines that
// differ in any of them get their own entry, never one another's operators. The first caller of
// a key builds it while later callers of that key wait for it (machines prepared in parallel do
// not build one operator twice); callers of other keys do not wait.
//
// Thread-safe. What it hands out is immutable, except each IdentificationOperator copy's own
// workspace (identification_operator.h), so machines on different threads share it freely.
#pragma once

#include <cstddef>
#include <cstdint>
#include <list>
#include <memory>
#include <mutex>
#include <optional>

#include "core/common/frf_matrix.h"
#include "core/common/result.h"
#include "core/inverse/identification_operator.h"
#include "core/pipeline/block_processor.h"
#include "core/pipeline/frf_grid_mapping.h"
#include "core/pipeline/frf_power_table.h"

namespace gearpath {

class SharedFrfOperators {
 public:
  explicit SharedFrfOperators(std::shared_ptr<const FrfMatrix> decoupled);
  SharedFrfOperators(const SharedFrfOperators&) = delete;
  SharedFrfOperators& operator=(const SharedFrfOperators&) = delete;

  const FrfMatrix& decoupled() const noexcept { return *decoupled_; }

  // The decoupled FRF on the bin grid of `block_length`-sample blocks at `sample_rate_hz`.
  Result<FrfGridMapping> Mapping(std::size_t block_length, double sample_rate_hz);

  // The identification operator of that mapping: a copy sharing the per-bin factorisations,
  // with its own workspace (one per machine).
  Result<IdentificationOperator> Operator(std::size_t block_length, double sample_rate_hz,
                                          const IdentificationOptions& options);

  // |H|^2 of that mapping (the path-energy stage's table), read-only and shared.
  Result<std::shared_ptr<const FrfPowerTable>> Power(std::size_t block_length,
                                                     double sample_rate_hz);

  // How many grid mappings, operators and power tables were built (successfully) so far
  // (tests: sharing, not rebuilding).
  std::uint64_t mappings_built() const;
  std::uint64_t operators_built() const;
  std::uint64_t power_tables_built() const;

 private:
  struct MappingEntry {
    std::size_t block_length = 0;
    double sample_rate_hz = 0.0;
    std::once_flag once;
    std::optional<Result<FrfGridMapping>> built;
  };
  struct OperatorEntry {
    std::size_t block_length = 0;
    double sample_rate_hz = 0.0;
    IdentificationOptions options;
    std::once_flag once;
    std::optional<Result<IdentificationOperator>> built;
  };
  struct PowerEntry {
    std::size_t block_length = 0;
    double sample_rate_hz = 0.0;
    std::once_flag once;
    std::optional<Result<std::shared_ptr<const FrfPowerTable>>> built;
  };

  std::shared_ptr<const FrfMatrix> decoupled_;
  mutable std::mutex mutex_;  // guards the lists and the counters, never held while building
  std::list<MappingEntry> mappings_;    // list: entries stay put while others are added
  std::list<OperatorEntry> operators_;
  std::list<PowerEntry> powers_;
  std::uint64_t mappings_built_ = 0;
  std::uint64_t operators_built_ = 0;
  std::uint64_t power_tables_built_ = 0;
};

// Same frequencies and same matrices, value for value.
bool SameFrfMatrix(const FrfMatrix& a, const FrfMatrix& b) noexcept;

// With `setup.shared_frf` set: checks that it holds exactly `setup.frf_set.decoupled` (same
// frequencies and values) and empties the setup's own copy, which the shared one replaces.
// Without it: nothing. BlockProcessor::Create calls it once the setup is validated.
Status DropOwnDecoupledCopy(MachineSetup& setup);

}  // namespace gearpath
