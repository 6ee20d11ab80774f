#include "tests/interop/cyclone_sample_json.h"

#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>

#include "tests/interop/idl_field_lists.h"

namespace gearpath::testing {
namespace {

// One field's value; nested structs go back through ToJson.
template <typename T>
nlohmann::json Value(const T& v) {
  if constexpr (std::is_enum_v<T>) {
    return static_cast<std::int64_t>(v);
  } else if constexpr (std::is_arithmetic_v<T>) {
    return v;
  } else if constexpr (std::is_array_v<T>) {
    using Element = std::remove_extent_t<T>;
    if constexpr (std::is_same_v<Element, char>) {  // bounded string: char[bound + 1]
      return std::string(v, strnlen(v, std::extent_v<T>));
    } else {  // IDL array
      nlohmann::json a = nlohmann::json::array();
      for (const Element& x : v) a.push_back(Value(x));
      return a;
    }
  } else if constexpr (requires {
                         v._buffer;
                         v._length;
                       }) {  // IDL sequence
    nlohmann::json a = nlohmann::json::array();
    for (std::uint32_t i = 0; i < v._length; ++i) a.push_back(Value(v._buffer[i]));
    return a;
  } else {
    return ToJson(v);
  }
}

}  // namespace

// idlc's types carry each field as a member of the field's name.
#define GEARPATH_CYCLONE_FIELD(name) j[#name] = Value(s.name);
#define GEARPATH_CYCLONE_TO_JSON(Type)                       \
  nlohmann::json ToJson(const gearpath_##Type& s) {          \
    nlohmann::json j = nlohmann::json::object();             \
    GEARPATH_FIELDS_##Type(GEARPATH_CYCLONE_FIELD) return j; \
  }

GEARPATH_CYCLONE_TO_JSON(PathShare)
GEARPATH_CYCLONE_TO_JSON(DominantPath)
GEARPATH_CYCLONE_TO_JSON(SuspectedGear)
GEARPATH_CYCLONE_TO_JSON(KurtogramBand)
GEARPATH_CYCLONE_TO_JSON(ShaftIndicator)
GEARPATH_CYCLONE_TO_JSON(EnvelopeIndicators)
GEARPATH_CYCLONE_TO_JSON(IndicatorValue)
GEARPATH_CYCLONE_TO_JSON(IndicatorSet)
GEARPATH_CYCLONE_TO_JSON(ConditionIndicators)
GEARPATH_CYCLONE_TO_JSON(MachineStatus)
GEARPATH_CYCLONE_TO_JSON(Status)
GEARPATH_CYCLONE_TO_JSON(MachineHealth)

}  // namespace gearpath::testing
