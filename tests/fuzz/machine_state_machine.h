// The machine of fuzz_machine_state (identity FRFs, two channels, 1024-sample blocks at 2048 Hz,
// a three-block baseline), as gearpathd's configuration. Its seed state files in
// tests/fuzz/corpus/fuzz_machine_state were saved by it, and so was
// tests/data/state/fingerprint_v1.state.json, which tests/daemon/saved_state_compatibility_test.cc
// resumes as the build of 2026-11-29 saved it: change this machine and that file no longer fits.
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
