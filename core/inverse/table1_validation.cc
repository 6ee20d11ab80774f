#include "core/inverse/table1_validation.h"

#include <cmath>
#include <random>

#include "core/frf/frac.h"
#include "core/frf/virtual_decoupling.h"
#include "core/inverse/identification_operator.h"
#include "core/model/lumped_gearbox_model.h"

namespace gearpath {
namespace {

double MaxRelativeError(const FrfMatrix& a, const FrfMatrix& b, Eigen::Index i, Eigen::Index j) {
  double worst = 0.0;
  for (Eigen::Index k = 0; k < a.bins(); ++k) {
    worst = std::max(worst, std::abs(a.at[k](i, j) - b.at[k](i, j)) / std::abs(b.at[k](i, j)));
  }
  return worst;
}

Eigen::VectorXcd Entry(const FrfMatrix& m, Eigen::Index i, Eigen::Index j) {
  Eigen::VectorXcd v(m.bins());
  for (Eigen::Index k = 0; k < m.bins(); ++k) v(k) = m.at[k](i, j);
  return v;
}

IdentificationOptions Options(InverseMethod method, RegularisationRule rule) {
  IdentificationOptions o;
  o.method = method;
  o.regularisation.rule = rule;
  return o;
}

}  // namespace

Result<Table1ValidationResult> ValidateOnTable1Model(const Table1ValidationOptions& options) {
  if (options.draws < 1) return Error{"draws: need at least 1 noise draw"};
  if (options.bins < 2) return Error{"bins: need at least 2 frequency bins"};
  if (!(options.f_lo_hz > 0.0) || !(options.f_hi_hz > options.f_lo_hz)) {
    return Error{"band: need 0 < f_lo < f_hi"};
  }
  Result<LumpedGearboxModel> model = LumpedGearboxModel::Create(Table1Parameters());
  if (!model) return Error{model.error()};
  const Eigen::VectorXd grid =
      Eigen::VectorXd::LinSpaced(options.bins, options.f_lo_hz, options.f_hi_hz);
  Result<CoupledBlocks> blocks = model->CoupledBlocksOnGrid(grid);
  if (!blocks) return Error{blocks.error()};
  Result<VirtualDecouplingResult> pp = DecoupleAtInterface(*blocks);
  if (!pp) return Error{pp.error()};
  Result<VirtualDecouplingResult> mp = DecoupleAtMeasurementPoints(*blocks);
  if (!mp) return Error{mp.error()};
  Result<FrfMatrix> physical_pp = model->PhysicalDecoupledPp(grid);
  Result<FrfMatrix> physical_mp = model->PhysicalDecoupledMp(grid);
  if (!physical_pp || !physical_mp) return Error{"physical decoupling of the Table-1 model failed"};

  Table1ValidationResult result;
  const Eigen::Index seats = model->rotor_count();
  auto add_entries = [&](const std::string& system, const FrfMatrix& v, const FrfMatrix& p,
                         bool housing_rows) -> Status {
    for (Eigen::Index i = 0; i < v.outputs(); ++i) {
      for (Eigen::Index j = 0; j < v.inputs(); ++j) {
        const Eigen::Index label_i = housing_rows ? 4 + seats : 4 + i;
        Result<double> frac = Frac(grid, Entry(v, i, j), Entry(p, i, j), options.f_lo_hz,
                                   options.f_hi_hz);
        if (!frac) return Error{frac.error()};
        result.decoupling.push_back({system,
                                     "H_" + std::to_string(label_i) + std::to_string(4 + j),
                                     MaxRelativeError(v, p, i, j), *frac});
      }
    }
    return Status::Ok();
  };
  if (Status s = add_entries("H_d,mp", mp->decoupled, *physical_mp, true); !s) {
    return Error{s.error()};
  }
  if (Status s = add_entries("H_d,pp", pp->decoupled, *physical_pp, false); !s) {
    return Error{s.error()};
  }

  // Stacked system and the true forces under mesh (transmission-error) excitation.
  FrfMatrix stacked;
  stacked.frequency_hz = grid;
  Eigen::MatrixXcd x(seats + 1, grid.size());
  Eigen::MatrixXcd forces(seats, grid.size());
  Eigen::VectorXcd te(model->stage_count());
  for (int s = 0; s < model->stage_count(); ++s) te(s) = Complex(1e-6, -0.4e-6 * s);
  for (Eigen::Index k = 0; k < grid.size(); ++k) {
    Eigen::MatrixXcd h(seats + 1, seats);
    h << pp->decoupled.at[k], mp->decoupled.at[k];
    stacked.at.push_back(h);
    Result<ForcedResponse> r = model->RespondToTransmissionError(grid(k), te);
    if (!r) return Error{r.error()};
    // The model's FRFs and its forced-response accelerations are both physical (a = -w^2 X).
    for (int i = 0; i < static_cast<int>(seats); ++i) {
      x(i, k) = r->acceleration(model->SeatDof(i));
    }
    x(seats, k) = r->acceleration(model->HousingDof());
    forces.col(k) = r->bearing_force;
  }

  struct Candidate {
    std::string name;
    IdentificationOptions options;
  };
  std::vector<Candidate> candidates{
      {"MWI (gcv, K=10)", Options(InverseMethod::kMwi, RegularisationRule::kGcv)},
      {"MWI (noise_floor eta=1e-3, K=10)",
       Options(InverseMethod::kMwi, RegularisationRule::kNoiseFloor)},
      {"Tikhonov (gcv)", Options(InverseMethod::kTikhonov, RegularisationRule::kGcv)},
      {"least squares", Options(InverseMethod::kLeastSquares, RegularisationRule::kFixed)},
  };
  std::vector<IdentificationOperator> operators;
  for (const Candidate& c : candidates) {
    Result<IdentificationOperator> op = IdentificationOperator::Create(stacked, c.options);
    if (!op) return Error{c.name + ": " + op.error()};
    operators.push_back(std::move(*op));
    result.methods.push_back({c.name, {}});
  }
  IdentificationOptions converged = Options(InverseMethod::kMwi, RegularisationRule::kFixed);
  converged.regularisation.parameter = 1e-8;
  converged.iterations = 100000;
  Result<IdentificationOperator> reference = IdentificationOperator::Create(stacked, converged);
  if (!reference) return Error{reference.error()};
  Eigen::MatrixXcd estimate(seats, grid.size());
  if (reference->IdentifyAll(x, estimate) != IdentifyStatus::kOk) {
    return Error{"identification failed on the noise-free responses"};
  }
  result.noise_free_error_mwi = (estimate - forces).norm() / forces.norm();

  // Noise scale per bin: the RMS over channels of that bin's response. (A scale fixed over the
  // band would bury the low-frequency bins, where accelerations ~ w^2 are tiny but the mesh
  // forces are not, under noise many times their size.)
  const Eigen::VectorXd bin_rms =
      x.colwise().norm().transpose() / std::sqrt(static_cast<double>(x.rows()));
  std::mt19937_64 engine(options.seed);
  std::normal_distribution<double> normal(0.0, std::sqrt(0.5));  // E|n|^2 = 1 for re + j im
  result.noise_levels = options.noise_levels;
  for (IdentificationMethodResult& m : result.methods) m.mean_error.assign(options.noise_levels.size(), 0.0);
  Eigen::MatrixXcd noisy(x.rows(), x.cols());
  for (std::size_t l = 0; l < options.noise_levels.size(); ++l) {
    for (int d = 0; d < options.draws; ++d) {
      for (Eigen::Index k = 0; k < x.cols(); ++k) {
        for (Eigen::Index i = 0; i < x.rows(); ++i) {
          noisy(i, k) = x(i, k) + options.noise_levels[l] * bin_rms(k) *
                                      Complex(normal(engine), normal(engine));
        }
      }
      for (std::size_t m = 0; m < operators.size(); ++m) {
        if (operators[m].IdentifyAll(noisy, estimate) != IdentifyStatus::kOk) {
          return Error{candidates[m].name + ": identification failed"};
        }
        result.methods[m].mean_error[l] +=
            (estimate - forces).norm() / forces.norm() / options.draws;
      }
    }
  }
  return result;
}

}  // namespace gearpath
