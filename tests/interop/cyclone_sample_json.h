// JSON of a sample as a Cyclone DDS reader decoded it (idlc's C types, the project's own
// binding), in exactly the form fastdds_sample_json.h gives the Fast DDS decoding of the same
// sample: every field under its IDL name, enums as numbers, bounded strings as strings,
// sequences and arrays as JSON arrays.
#pragma once

#include <nlohmann/json.hpp>

#include "idl/dds/gearpath_topics.h"

namespace gearpath::testing {

nlohmann::json ToJson(const gearpath_PathShare& s);
nlohmann::json ToJson(const gearpath_DominantPath& s);
nlohmann::json ToJson(const gearpath_SuspectedGear& s);
nlohmann::json ToJson(const gearpath_KurtogramBand& s);
nlohmann::json ToJson(const gearpath_ShaftIndicator& s);
nlohmann::json ToJson(const gearpath_EnvelopeIndicators& s);
nlohmann::json ToJson(const gearpath_IndicatorValue& s);
nlohmann::json ToJson(const gearpath_IndicatorSet& s);
nlohmann::json ToJson(const gearpath_ConditionIndicators& s);
nlohmann::json ToJson(const gearpath_MachineStatus& s);
nlohmann::json ToJson(const gearpath_Status& s);
nlohmann::json ToJson(const gearpath_MachineHealth& s);

}  // namespace gearpath::testing
