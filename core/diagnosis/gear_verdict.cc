#include "core/diagnosis/gear_verdict.h"

namespace gearpath {

std::string_view ToString(FaultState state) noexcept {
  switch (state) {
    case FaultState::kLearning:
      return "learning";
    case FaultState::kNoFault:
      return "no_fault";
    case FaultState::kSuspected:
      return "suspected";
    case FaultState::kAlarm:
      return "alarm";
  }
  return "unknown";
}

void VerdictTopology::Reserve(GearVerdict& verdict) const {
  verdict.candidates.reserve(gear_names.size());
  verdict.candidate_names.reserve(gear_names.size());
}

}  // namespace gearpath
