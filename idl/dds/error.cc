#include "idl/dds/error.h"

#include <stdexcept>

namespace gearpath::dds {

std::string DdsErrorMessage(std::string_view call, dds_return_t rc) {
  std::string message(call);
  message += " failed: ";
  message += dds_strretcode(rc);
  message += " (";
  message += std::to_string(rc);
  message += ")";
  return message;
}

dds_return_t CheckDds(dds_return_t rc, std::string_view call) {
  if (rc < 0) throw std::runtime_error(DdsErrorMessage(call, rc));
  return rc;
}

}  // namespace gearpath::dds
