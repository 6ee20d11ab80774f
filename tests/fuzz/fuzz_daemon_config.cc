// libFuzzer target: gearpathd's configuration parser (JSON, schema, cross-key rules).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "daemon/daemon_config.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  (void)gearpath::daemon::ParseDaemonConfig(text, "fuzz.json");
  return 0;
}
