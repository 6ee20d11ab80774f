// Validation of decoupling and force identification on the seed's Table-1 model: the numbers
// behind the seed's Fig. 5 (virtual vs physical decoupling) and Table 2 (identification error
// of MWI and Tikhonov under response noise), recomputed. Printed by `gearpath validate`.
//
// Decoupling: H_d,pp (Eq. 22) and H_d,mp (Eq. 24) from the coupled model's FRFs against the
// housing-alone FRFs, per entry: max over bins of |virtual - physical| / |physical| and FRAC
// (Eq. 25). Seed labels: seats are masses 4, 5, 6, the housing mass is 7.
// Identification: mesh-excited bearing forces (Eq. 44) from the model; responses x = seat and
// housing accelerations; system [H_d,pp; H_d,mp] (4 x 3, overdetermined so GCV is well posed,
// see regularisation_rule.h); noise: independent complex Gaussian per channel and bin with
// E|n|^2 = (level * RMS over channels of that bin's response)^2, `draws` draws from a fixed
// seed; error = ||F_hat - F||_F / ||F||_F over all bins and paths, averaged over draws.
#pragma once

#include <string>
#include <vector>

#include "core/common/result.h"

namespace gearpath {

struct Table1ValidationOptions {
  int draws = 20;
  unsigned seed = 1;
  double f_lo_hz = 1.0;
  double f_hi_hz = 4000.0;
  int bins = 400;
  std::vector<double> noise_levels{1e-4, 1e-3, 1e-2};
};

struct DecouplingEntryError {
  std::string system;  // "H_d,mp" or "H_d,pp"
  std::string entry;   // e.g. "H_47"
  double max_relative_error = 0.0;
  double frac = 0.0;
};

struct IdentificationMethodResult {
  std::string name;  // e.g. "MWI (gcv, K=10)"
  std::vector<double> mean_error;  // one per noise level
};

struct Table1ValidationResult {
  std::vector<DecouplingEntryError> decoupling;
  std::vector<double> noise_levels;
  std::vector<IdentificationMethodResult> methods;
  double noise_free_error_mwi = 0.0;  // converged MWI, no noise (sanity: ~1e-12)
};

Result<Table1ValidationResult> ValidateOnTable1Model(const Table1ValidationOptions& options);

}  // namespace gearpath
