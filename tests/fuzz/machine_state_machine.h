// The machine of fuzz_machine_state (identity FRFs, two channels, 1024-sample blocks at 2048 Hz,
// a three-block baseline), as gearpathd's configuration: its seed state files in
// tests/fuzz/corpus/fuzz_machine_state were saved by it, so a test that builds the same machine
// can resume them as a build of that day saved them.
#pragma once

namespace gearpath {

inline constexpr char kMachineStateConfig[] = R"({
  "machines": [{
    "id": "fuzz", "frf_set": "identity", "nominal_speed_hz": 10.0,
    "acquisition": {"sample_rate_hz": 2048.0, "min_samples_per_channel": 1024,
                    "max_samples_per_channel": 1024, "prepare_samples_per_channel": [1024]},
    "channels": [{"sensor": "A1", "axis": "x", "gears": ["G1", "G2"]},
                 {"sensor": "A2", "axis": "z", "gears": ["G3", "G4"]}],
    "gear_train": {
      "shafts": [{"name": "input", "gears": ["G1"]},
                 {"name": "intermediate", "gears": ["G2", "G3"]},
                 {"name": "output", "gears": ["G4"]}],
      "gears": [{"name": "G1", "teeth": 28}, {"name": "G2", "teeth": 40},
                {"name": "G3", "teeth": 34}, {"name": "G4", "teeth": 34}],
      "stages": [{"driver": "G1", "driven": "G2"}, {"driver": "G3", "driven": "G4"}]},
    "analysis": {"baseline": {"learning_blocks": 3, "epoch": "fuzz"}}
  }]
})";

}  // namespace gearpath
