// libFuzzer target: the DH8303-style text export reader.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/io/text_export.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  (void)gearpath::ParseTextExport(text, "fuzz.txt");
  return 0;
}
