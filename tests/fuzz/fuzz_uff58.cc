// libFuzzer target: the UFF dataset 58 reader.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/io/uff58.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  (void)gearpath::ParseUff58(text, "fuzz.uff");
  return 0;
}
