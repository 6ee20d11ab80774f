// libFuzzer targets: the FRF set manifest reader (FUZZ_FRF_SET) or the recording manifest
// reader (FUZZ_RECORDING). Both read a directory, so the fuzzer's input becomes manifest.json
// next to valid arrays written once at start-up: a mutated manifest can get past the JSON
// into the key checks and the array loading.
#include <unistd.h>

#include <complex>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/io/frf_set_io.h"
#include "core/io/recording.h"

namespace {

namespace fs = std::filesystem;

fs::path Dir() {
  static const fs::path dir =
      fs::temp_directory_path() / ("gearpath_fuzz_" + std::to_string(::getpid()));
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  using namespace gearpath;
  fs::remove_all(Dir());
#if defined(FUZZ_FRF_SET)
  FrfSet set;
  set.description = "fuzz seed";
  set.quantity = FrfQuantity::kAccelerance;
  set.unit = "m/s^2/N";
  set.decoupling = "eq22";
  set.paths = {{"B1x", "B1", "x", {"G1"}}};
  set.channels = {{"A1", "x"}};
  set.decoupled.frequency_hz = Eigen::VectorXd::LinSpaced(4, 10.0, 40.0);
  set.decoupled.at.assign(4, Eigen::MatrixXcd::Constant(1, 1, std::complex<double>(1.0, 0.5)));
  if (Status st = WriteFrfSet(set, Dir()); !st) return 1;
#else
  Recording r;
  r.layout.machine_id = "fuzz";
  r.layout.sample_rate_hz = 1000.0;
  r.layout.channels = {{"A1", Axis::kX, "m/s^2", 100.0}};
  r.layout.samples_per_channel = 4;
  r.blocks = {{1, 0, 10.0, SpeedSource::kAcquisition}};
  r.samples = {0.0f, 1.0f, 2.0f, 3.0f};
  if (Status st = WriteRecording(r, Dir()); !st) return 1;
#endif
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  {
    std::ofstream out(Dir() / "manifest.json", std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
#if defined(FUZZ_FRF_SET)
  (void)gearpath::ReadFrfSet(Dir());
#else
  (void)gearpath::ReadRecording(Dir());
  (void)gearpath::IsRecordingDirectory(Dir());
#endif
  return 0;
}
