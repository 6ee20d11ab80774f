#include "tests/interop/fastdds_sample_json.h"

#include <cstdint>
#include <type_traits>

#include "tests/interop/idl_field_lists.h"

namespace gearpath_interop {
namespace {

// One field's value; nested structs go back through ToJson.
template <typename T>
nlohmann::json Value(const T& v) {
  if constexpr (std::is_enum_v<T>) {
    return static_cast<std::int64_t>(v);
  } else if constexpr (std::is_arithmetic_v<T>) {
    return v;
  } else if constexpr (requires { v.to_string(); }) {  // fixed_string<N>: a bounded string
    return v.to_string();
  } else if constexpr (requires {
                         v.begin();
                         v.end();
                       }) {  // std::vector, std::array
    nlohmann::json a = nlohmann::json::array();
    for (const auto& x : v) a.push_back(Value(x));
    return a;
  } else {
    return ToJson(v);
  }
}

}  // namespace

// fastddsgen's types expose each field through an accessor of the field's name.
#define GEARPATH_FASTDDS_FIELD(name) j[#name] = Value(s.name());
#define GEARPATH_FASTDDS_TO_JSON(Type)                       \
  nlohmann::json ToJson(const gearpath::Type& s) {           \
    nlohmann::json j = nlohmann::json::object();             \
    GEARPATH_FIELDS_##Type(GEARPATH_FASTDDS_FIELD) return j; \
  }

GEARPATH_FASTDDS_TO_JSON(PathShare)
GEARPATH_FASTDDS_TO_JSON(DominantPath)
GEARPATH_FASTDDS_TO_JSON(SuspectedGear)
GEARPATH_FASTDDS_TO_JSON(KurtogramBand)
GEARPATH_FASTDDS_TO_JSON(ShaftIndicator)
GEARPATH_FASTDDS_TO_JSON(EnvelopeIndicators)
GEARPATH_FASTDDS_TO_JSON(IndicatorValue)
GEARPATH_FASTDDS_TO_JSON(IndicatorSet)
GEARPATH_FASTDDS_TO_JSON(ConditionIndicators)
GEARPATH_FASTDDS_TO_JSON(MachineStatus)
GEARPATH_FASTDDS_TO_JSON(Status)
GEARPATH_FASTDDS_TO_JSON(MachineHealth)

}  // namespace gearpath_interop
