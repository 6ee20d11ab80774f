#include "core/evaluation/plant_stream.h"

#include <cmath>
#include <memory>
#include <utility>

#include "core/evaluation/linear_plant_stream.h"
#include "core/evaluation/parametric_gearbox.h"
#include "core/evaluation/parametric_plant_simulator.h"
#include "core/evaluation/parametric_plate_plant.h"
#include "core/evaluation/plant_simulator.h"

namespace gearpath {
namespace {

Result<std::unique_ptr<PlantStream>> MakeLinearStream(const Plant& plant, const Scenario& sc,
                                                      const PlantStreamConfig& config) {
  if (!(config.load_factor > 0.0) || !std::isfinite(config.load_factor)) {
    return Error{"plant stream: load_factor must be finite and > 0"};
  }
  PlantExcitationConfig ex;
  ex.fault = sc.fault;
  ex.faulty_gear = sc.gear;
  ex.seed = sc.seed;
  ex.mesh_fundamental_m *= config.load_factor;
  Result<PlantExcitation> excitation = PlantExcitation::Create(plant.train, ex);
  if (!excitation) return Error{excitation.error()};
  PlantSimulatorConfig sim_config;
  sim_config.machine_id = config.machine_id;
  sim_config.sample_rate_hz = config.sample_rate_hz;
  sim_config.block_length = config.block_length;
  sim_config.first_sequence = config.first_sequence;
  sim_config.start_time_ns = config.start_time_ns;
  sim_config.input_speed_hz = sc.input_rpm / 60.0;
  sim_config.noise_relative = sc.noise;
  sim_config.tones = sc.unmodelled;
  sim_config.bursts = sc.unmodelled;
  sim_config.speed_drift = sc.unmodelled;
  sim_config.seed = sc.seed;
  Result<PlantSimulator> sim = PlantSimulator::Create(plant.dynamics, plant.channels,
                                                      std::move(excitation).value(), sim_config);
  if (!sim) return Error{sim.error()};
  return std::unique_ptr<PlantStream>(
      std::make_unique<LinearPlantStream>(std::move(sim).value()));
}

Result<std::unique_ptr<PlantStream>> MakeParametricStream(const Plant& plant, const Scenario& sc,
                                                          const PlantStreamConfig& config) {
  if (!plant.parametric) return Error{"parametric stream: the plant has no parametric truth"};
  if (!(config.load_factor > 0.0) || !std::isfinite(config.load_factor)) {
    return Error{"parametric stream: load_factor must be finite and > 0"};
  }
  std::shared_ptr<const ParametricGearbox> truth = plant.parametric->truth;
  if (config.load_factor != 1.0) {
    ParametricGearboxParameters p = truth->parameters();
    p.load_torque_nm *= config.load_factor;
    p.load_damping_nms_per_rad *= config.load_factor;
    Result<ParametricGearbox> loaded = ParametricGearbox::Create(std::move(p));
    if (!loaded) return Error{"parametric stream: load step: " + loaded.error()};
    truth = std::make_shared<const ParametricGearbox>(std::move(loaded).value());
  }
  Result<ToothFault> fault =
      DrawToothFault(*plant.parametric, plant.train, sc.fault, sc.gear, sc.seed);
  if (!fault) return Error{fault.error()};
  ParametricSimulatorConfig c;
  c.machine_id = config.machine_id;
  c.sample_rate_hz = config.sample_rate_hz;
  c.block_length = config.block_length;
  c.first_sequence = config.first_sequence;
  c.start_time_ns = config.start_time_ns;
  c.input_speed_hz = sc.input_rpm / 60.0;
  c.noise_relative = sc.noise;
  c.tones = sc.unmodelled;
  c.bursts = sc.unmodelled;
  c.speed_drift = sc.unmodelled;
  c.seed = sc.seed;
  Result<ParametricPlantSimulator> sim =
      ParametricPlantSimulator::Create(std::move(truth), plant.parametric->channel_points,
                                       plant.channels, std::move(fault).value(), c);
  if (!sim) return Error{sim.error()};
  return std::unique_ptr<PlantStream>(
      std::make_unique<ParametricPlantSimulator>(std::move(sim).value()));
}

}  // namespace

Result<std::unique_ptr<PlantStream>> MakePlantStream(const Plant& plant, const Scenario& scenario,
                                                     const PlantStreamConfig& config) {
  if (plant.dynamics) return MakeLinearStream(plant, scenario, config);
  if (plant.parametric) return MakeParametricStream(plant, scenario, config);
  return Error{"plant stream: the plant has no truth (dynamics or parametric)"};
}

}  // namespace gearpath
