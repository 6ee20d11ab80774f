// WaitSet, GuardCondition, ReadCondition: blocking in the application's own threads.
//
// Cyclone runs listeners on its own threads, where calling back into DDS entities can
// deadlock, so gearpath reads only from its own threads: a worker attaches a ReadCondition
// (data available) and a GuardCondition (shutdown) to a WaitSet and waits on it; shutdown
// triggers the guard condition, which wakes the wait at once, and the worker returns.
#pragma once

#include <dds/dds.h>

#include <chrono>
#include <cstddef>
#include <span>

#include "core/common/result.h"
#include "idl/dds/domain.h"
#include "idl/dds/entity.h"

namespace gearpath::dds {

class GuardCondition : public Entity {
 public:
  explicit GuardCondition(const Participant& participant);  // throws std::runtime_error

  // Sets the condition (wakes every WaitSet it is attached to). Thread-safe.
  Status Trigger() noexcept;
  // Reads and clears the condition: true if it was triggered.
  Result<bool> TakeTriggered() noexcept;
};

class ReadCondition : public Entity {
 public:
  // Triggers while `reader` (any Reader<T>) holds samples matching `mask` (a combination of
  // DDS_*_SAMPLE_STATE, DDS_*_VIEW_STATE, DDS_*_INSTANCE_STATE; default: any sample).
  explicit ReadCondition(const Entity& reader, std::uint32_t mask = DDS_ANY_STATE);
};

class WaitSet : public Entity {
 public:
  explicit WaitSet(const Participant& participant);  // throws std::runtime_error

  // Attaches a condition (or any entity with a status condition); `token` is reported back by
  // Wait when it triggers. Throws std::runtime_error naming dds_waitset_attach. The condition
  // must stay alive while attached (Cyclone detaches it if it is deleted).
  void Attach(const Entity& condition, dds_attach_t token);
  Status Detach(const Entity& condition) noexcept;

  // Blocks until at least one attached condition triggers or `timeout` passes; writes the
  // tokens of the triggered conditions (up to triggered.size()) and returns how many
  // triggered (0 on timeout).
  Result<std::size_t> Wait(std::span<dds_attach_t> triggered,
                           std::chrono::nanoseconds timeout) noexcept;
};

}  // namespace gearpath::dds
