#include "idl/dds/waitset.h"

#include <limits>
#include <string>

#include "idl/dds/error.h"

namespace gearpath::dds {

GuardCondition::GuardCondition(const Participant& participant)
    : Entity(CheckDds(dds_create_guardcondition(participant.handle()), "dds_create_guardcondition"),
             participant.node()) {}

Status GuardCondition::Trigger() noexcept {
  const dds_return_t rc = dds_set_guardcondition(handle(), true);
  if (rc < 0) return Error{DdsErrorMessage("dds_set_guardcondition", rc)};
  return Status::Ok();
}

Result<bool> GuardCondition::TakeTriggered() noexcept {
  bool triggered = false;
  const dds_return_t rc = dds_take_guardcondition(handle(), &triggered);
  if (rc < 0) return Error{DdsErrorMessage("dds_take_guardcondition", rc)};
  return triggered;
}

ReadCondition::ReadCondition(const Entity& reader, std::uint32_t mask)
    : Entity(CheckDds(dds_create_readcondition(reader.handle(), mask), "dds_create_readcondition"),
             reader.node()) {}

WaitSet::WaitSet(const Participant& participant)
    : Entity(CheckDds(dds_create_waitset(participant.handle()), "dds_create_waitset"),
             participant.node()) {}

void WaitSet::Attach(const Entity& condition, dds_attach_t token) {
  CheckDds(dds_waitset_attach(handle(), condition.handle(), token), "dds_waitset_attach");
}

Status WaitSet::Detach(const Entity& condition) noexcept {
  const dds_return_t rc = dds_waitset_detach(handle(), condition.handle());
  if (rc < 0) return Error{DdsErrorMessage("dds_waitset_detach", rc)};
  return Status::Ok();
}

Result<std::size_t> WaitSet::Wait(std::span<dds_attach_t> triggered,
                                  std::chrono::nanoseconds timeout) noexcept {
  const dds_return_t rc = dds_waitset_wait(handle(), triggered.data(), triggered.size(),
                                           static_cast<dds_duration_t>(timeout.count()));
  if (rc < 0) return Error{DdsErrorMessage("dds_waitset_wait", rc)};
  return static_cast<std::size_t>(rc);
}

}  // namespace gearpath::dds
