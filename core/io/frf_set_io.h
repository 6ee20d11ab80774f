// FRF set on disk: a directory holding manifest.json plus NumPy .npy arrays.
//
// This is the documented, versioned format of docs/frf_format.md (format "gearpath-frf-set",
// format_version 1), chosen so that a Python user can read and write a set with json + numpy
// alone. It carries the decoupled FRF matrix the daemon inverts (seed Eqs. 22/24 output), the
// coupled blocks it came from (Eqs. 22/24 input, Fig. 2 roles a/p/m), or both, on one strictly
// increasing frequency axis in Hz. Arrays are complex128, C order, shaped (n_freq, rows, cols).
//
// The reader trusts nothing: every error names the file and the manifest key or array index
// at fault. The writer refuses a set the reader would reject, writes the arrays first and the
// manifest last (a crash mid-write leaves no manifest, hence no loadable half set), and its
// output reads back bit for bit.
#pragma once

#include <filesystem>
#include <string>

#include "core/common/result.h"
#include "core/frf/frf_set.h"

namespace gearpath {

inline constexpr char kFrfSetFormatName[] = "gearpath-frf-set";
inline constexpr char kFrfSetManifestName[] = "manifest.json";

// "accelerance", "mobility", "receptance".
const char* FrfQuantityName(FrfQuantity quantity) noexcept;
// The SI unit the format requires for each quantity: "m/s^2/N", "m/s/N", "m/N".
const char* FrfQuantitySiUnit(FrfQuantity quantity) noexcept;

// Checks what the manifest describes (quantity/unit agreement, decoupling label, path, channel
// and DOF names and directions, one of decoupled/coupled present, array shapes and finiteness,
// frequency axis). Messages use manifest key paths, e.g. "paths[2].direction".
Status ValidateFrfSet(const FrfSet& set);

// Reads the set in `dir`. Errors name the file and the key or index at fault.
Result<FrfSet> ReadFrfSet(const std::filesystem::path& dir);

// Writes `set` into `dir` (created if needed; existing set files are overwritten).
Status WriteFrfSet(const FrfSet& set, const std::filesystem::path& dir);

}  // namespace gearpath
