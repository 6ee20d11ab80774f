#include "core/simulation/gearbox_simulator.h"

#include <cmath>
#include <complex>
#include <string>

#include "core/dsp/fft_plan.h"

namespace gearpath {
namespace {

constexpr std::uint64_t kNoiseStream = 3;

std::string Num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

}  // namespace

Status CheckTrainMatchesModel(const LumpedGearboxModel& model, const GearTrain& train) {
  if (Status st = train.Validate(); !st) return st;
  const std::size_t stages = static_cast<std::size_t>(model.stage_count());
  if (train.stages.size() != stages) {
    return Error{"gear train: has " + std::to_string(train.stages.size()) +
                 " stages but the model has " + std::to_string(stages)};
  }
  if (train.shafts.size() != stages + 1) {
    return Error{"gear train: has " + std::to_string(train.shafts.size()) +
                 " shafts but the model has " + std::to_string(stages + 1) + " rotors"};
  }
  for (std::size_t s = 0; s < stages; ++s) {
    const StageSpec& st = train.stages[s];
    const GearStage& ms = model.parameters().stages[s];
    const std::string label =
        "gear train: stages[" + std::to_string(s) + "] (" + st.driver + "->" + st.driven + ")";
    const int sd = train.ShaftOfGear(st.driver);
    const int sn = train.ShaftOfGear(st.driven);
    if (sd != static_cast<int>(s) || sn != static_cast<int>(s) + 1) {
      return Error{label + ": must drive from shaft " + std::to_string(s) + " to shaft " +
                   std::to_string(s + 1) + " (model rotors in train order), got shafts " +
                   std::to_string(sd) + " -> " + std::to_string(sn)};
    }
    const int zd = train.gears[static_cast<std::size_t>(train.GearIndex(st.driver))].teeth;
    const int zn = train.gears[static_cast<std::size_t>(train.GearIndex(st.driven))].teeth;
    if (zd != ms.z_driver || zn != ms.z_driven) {
      return Error{label + ": tooth counts " + std::to_string(zd) + "/" + std::to_string(zn) +
                   " differ from the model's " + std::to_string(ms.z_driver) + "/" +
                   std::to_string(ms.z_driven)};
    }
  }
  if (train.bearings.size() != stages + 1) {
    return Error{"gear train: has " + std::to_string(train.bearings.size()) +
                 " bearings but the model has " + std::to_string(stages + 1) +
                 " bearing seats (one per rotor)"};
  }
  for (std::size_t b = 0; b < train.bearings.size(); ++b) {
    if (train.ShaftIndex(train.bearings[b].shaft) != static_cast<int>(b)) {
      return Error{"gear train: bearings[" + std::to_string(b) + "] (" + train.bearings[b].name +
                   ") must support shaft '" + train.shafts[b].name + "' (model seat " +
                   std::to_string(b) + "), got '" + train.bearings[b].shaft + "'"};
    }
  }
  return Status::Ok();
}

Result<GearboxSimulator> GearboxSimulator::Create(const LumpedGearboxModel& model,
                                                  const GearTrain& train,
                                                  const SimulatorConfig& config) {
  const SimulatorConfig& c = config;
  if (!(c.sample_rate_hz > 0.0) || !std::isfinite(c.sample_rate_hz)) {
    return Error{"simulator: sample_rate_hz must be finite and > 0, got " + Num(c.sample_rate_hz)};
  }
  if (!(c.input_speed_hz > 0.0) || !std::isfinite(c.input_speed_hz)) {
    return Error{"simulator: input_speed_hz must be finite and > 0, got " + Num(c.input_speed_hz)};
  }
  if (c.block_length < 1) return Error{"simulator: block_length must be >= 1, got 0"};
  if (!(c.noise_relative >= 0.0) || !std::isfinite(c.noise_relative)) {
    return Error{"simulator: noise_relative must be finite and >= 0, got " + Num(c.noise_relative)};
  }
  if (Status st = CheckTrainMatchesModel(model, train); !st) {
    return Error{"simulator: " + st.error()};
  }
  const Result<std::int64_t> revolutions = train.InputRevolutionsPerCommonPeriod();
  if (!revolutions.ok()) return Error{"simulator: " + revolutions.error()};

  // One common period, snapped to a whole number of samples.
  const double period_s = static_cast<double>(*revolutions) / c.input_speed_hz;
  const double exact_samples = period_s * c.sample_rate_hz;
  if (exact_samples > static_cast<double>(c.max_period_samples)) {
    return Error{"simulator: the common period of all shafts (" + Num(period_s) +
                 " s = " + Num(exact_samples) + " samples) exceeds max_period_samples (" +
                 std::to_string(c.max_period_samples) + "); raise the speed or the limit"};
  }
  const auto n = static_cast<std::size_t>(std::llround(exact_samples));
  if (n < 4) {
    return Error{"simulator: the common period of all shafts is only " + Num(exact_samples) +
                 " samples at sample_rate_hz " + Num(c.sample_rate_hz) + "; raise the sample rate"};
  }
  const double speed_hz =
      static_cast<double>(*revolutions) * c.sample_rate_hz / static_cast<double>(n);

  ExcitationParameters excitation_parameters = c.excitation;
  excitation_parameters.seed = c.seed;
  Result<FaultExcitation> excitation =
      FaultExcitation::Create(train, speed_hz, c.fault, excitation_parameters);
  if (!excitation.ok()) return Error{"simulator: " + excitation.error()};

  GearboxSimulator sim(std::move(excitation).value());
  sim.config_ = c;
  sim.speed_hz_ = speed_hz;
  sim.noise_ = DeterministicRng(c.seed, kNoiseStream);

  const Eigen::Index stages = model.stage_count();
  const Eigen::Index seats = model.rotor_count();
  const Eigen::Index bins = static_cast<Eigen::Index>(n / 2 + 1);
  Eigen::VectorXd freq(bins);
  for (Eigen::Index k = 0; k < bins; ++k) {
    freq(k) = static_cast<double>(k) * c.sample_rate_hz / static_cast<double>(n);
  }
  Result<TransmissionErrorTransfer> transfer = model.TransmissionErrorTransferOnGrid(freq);
  if (!transfer.ok()) return Error{"simulator: " + transfer.error()};

  Result<FftPlan> forward = FftPlan::Create(FftKind::kRealToComplex, n);
  if (!forward.ok()) return Error{"simulator: " + forward.error()};
  Result<FftPlan> backward = FftPlan::Create(FftKind::kComplexToReal, n);
  if (!backward.ok()) return Error{"simulator: " + backward.error()};

  // TE spectra, one column per stage.
  sim.te_.resize(static_cast<Eigen::Index>(n), stages);
  Eigen::MatrixXcd te_spectrum(bins, stages);
  for (Eigen::Index s = 0; s < stages; ++s) {
    std::span<double> in = forward->real_in();
    sim.excitation_.Sample(static_cast<int>(s), 0.0, c.sample_rate_hz, in);
    const double mean =
        Eigen::Map<const Eigen::VectorXd>(in.data(), static_cast<Eigen::Index>(n)).mean();
    for (std::size_t i = 0; i < n; ++i) {
      sim.te_(static_cast<Eigen::Index>(i), s) = in[i] - mean;
    }
    forward->Execute();
    const std::span<std::complex<double>> out = forward->complex_out();
    for (Eigen::Index k = 0; k < bins; ++k) te_spectrum(k, s) = out[static_cast<std::size_t>(k)];
  }
  const bool has_nyquist = n % 2 == 0;

  // response(k) = T(k) E(k) for one output row of a transfer, then back to time.
  const auto synthesize = [&](const FrfMatrix& t, Eigen::Index row,
                              Eigen::Ref<Eigen::VectorXd> dst) {
    std::span<std::complex<double>> in = backward->complex_in();
    for (Eigen::Index k = 0; k < bins; ++k) {
      std::complex<double> y = 0.0;
      for (Eigen::Index s = 0; s < stages; ++s) {
        y += t.at[static_cast<std::size_t>(k)](row, s) * te_spectrum(k, s);
      }
      in[static_cast<std::size_t>(k)] = y;
    }
    in[0] = 0.0;
    if (has_nyquist) in[static_cast<std::size_t>(bins - 1)] = 0.0;
    backward->Execute();
    const std::span<double> out = backward->real_out();
    for (std::size_t i = 0; i < n; ++i) {
      dst(static_cast<Eigen::Index>(i)) = out[i] / static_cast<double>(n);
    }
  };

  const Eigen::Index channel_count = seats + (c.include_housing_channel ? 1 : 0);
  sim.acceleration_.resize(static_cast<Eigen::Index>(n), channel_count);
  sim.bearing_force_.resize(static_cast<Eigen::Index>(n), seats);
  for (Eigen::Index s = 0; s < seats; ++s) {
    synthesize(transfer->seat_acceleration, s, sim.acceleration_.col(s));
    synthesize(transfer->bearing_force, s, sim.bearing_force_.col(s));
    sim.channels_.push_back({"p" + std::to_string(s + 1), Axis::kX, "m/s^2", 0.0});
  }
  if (c.include_housing_channel) {
    synthesize(transfer->housing_acceleration, 0, sim.acceleration_.col(seats));
    sim.channels_.push_back({"m1", Axis::kX, "m/s^2", 0.0});
  }
  sim.noise_std_.resize(channel_count);
  for (Eigen::Index ch = 0; ch < channel_count; ++ch) {
    const double rms = std::sqrt(sim.acceleration_.col(ch).squaredNorm() / static_cast<double>(n));
    sim.noise_std_(ch) = c.noise_relative * rms;
  }
  return sim;
}

void GearboxSimulator::NextBlock(AccelBlock& block, std::vector<double>* bearing_forces) {
  const std::uint32_t len = config_.block_length;
  const std::size_t channels = channels_.size();
  const auto period = static_cast<std::uint64_t>(acceleration_.rows());
  block.machine_id = config_.machine_id;
  block.sequence = config_.first_sequence + blocks_;
  block.t0_ns = config_.start_time_ns +
                std::llround(static_cast<double>(position_) * 1e9 / config_.sample_rate_hz);
  block.sample_rate_hz = config_.sample_rate_hz;
  block.speed_hz = config_.report_speed ? speed_hz_ : 0.0;
  block.speed_source = config_.report_speed ? SpeedSource::kAcquisition : SpeedSource::kUnknown;
  if (block.channels.size() != channels) block.channels = channels_;
  for (std::size_t ch = 0; ch < channels; ++ch) {
    if (block.channels[ch].sensor != channels_[ch].sensor) block.channels[ch] = channels_[ch];
  }
  block.samples_per_channel = len;
  if (block.samples.size() != channels * len) block.samples.resize(channels * len);
  const auto start = static_cast<Eigen::Index>(position_ % period);
  // Noise is drawn channel by channel in the planar order, so the stream is fixed by the seed.
  for (std::size_t ch = 0; ch < channels; ++ch) {
    Eigen::Index i = start;
    const double sigma = noise_std_(static_cast<Eigen::Index>(ch));
    float* dst = block.samples.data() + ch * len;
    for (std::uint32_t j = 0; j < len; ++j) {
      double v = acceleration_(i, static_cast<Eigen::Index>(ch));
      if (sigma > 0.0) v += sigma * noise_.Gaussian();
      dst[j] = static_cast<float>(v);
      if (++i == acceleration_.rows()) i = 0;
    }
  }
  if (bearing_forces != nullptr) {
    const auto seats = static_cast<std::size_t>(bearing_force_.cols());
    if (bearing_forces->size() != seats * len) bearing_forces->resize(seats * len);
    for (std::size_t b = 0; b < seats; ++b) {
      Eigen::Index i = start;
      for (std::uint32_t j = 0; j < len; ++j) {
        (*bearing_forces)[b * len + j] = bearing_force_(i, static_cast<Eigen::Index>(b));
        if (++i == bearing_force_.rows()) i = 0;
      }
    }
  }
  position_ += len;
  ++blocks_;
}

void GearboxSimulator::Rewind() noexcept {
  position_ = 0;
  blocks_ = 0;
  noise_ = DeterministicRng(config_.seed, kNoiseStream);
}

}  // namespace gearpath
