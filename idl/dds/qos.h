// Qos: an owning, copyable builder over Cyclone's dds_qos_t, and the named QoS profiles of the
// three gearpath topic classes (docs/topics.md explains each choice).
//
// dds_qset_* cannot fail; an inconsistent combination (e.g. a history depth above the
// per-instance resource limit) is reported by the dds_create_* call that uses the QoS, whose
// error names that call. Readers are never left on Cyclone's defaults (best-effort, keep-last
// 1): every profile sets reliability, durability and history explicitly.
#pragma once

#include <dds/dds.h>

#include <chrono>
#include <cstdint>

namespace gearpath::dds {

class Qos {
 public:
  Qos();  // Cyclone defaults; throws std::bad_alloc if dds_create_qos fails
  ~Qos();
  Qos(const Qos& other);
  Qos& operator=(const Qos& other);
  Qos(Qos&& other) noexcept;
  Qos& operator=(Qos&& other) noexcept;

  Qos& Reliable(std::chrono::nanoseconds max_blocking_time);
  Qos& BestEffort();
  Qos& KeepLast(std::int32_t depth);
  Qos& KeepAll();
  Qos& Volatile();
  Qos& TransientLocal();
  // What a late-joining reader gets from a transient-local writer: Cyclone keeps this history
  // per instance in the writer for late joiners.
  Qos& DurabilityServiceKeepLast(std::int32_t depth);
  // DDS_LENGTH_UNLIMITED (-1) for no limit.
  Qos& ResourceLimits(std::int32_t max_samples, std::int32_t max_instances,
                      std::int32_t max_samples_per_instance);
  Qos& Deadline(std::chrono::nanoseconds period);
  Qos& LivelinessAutomatic(std::chrono::nanoseconds lease_duration);

  const dds_qos_t* get() const noexcept { return qos_; }

 private:
  dds_qos_t* qos_;
};

// The three classes of gearpath topic.
enum class TopicClass {
  kBlockStream,   // AccelBlock: every block matters, none may be lost silently
  kLatestResult,  // DominantPath, SuspectedGear, EnvelopeIndicators, ConditionIndicators: the
                  // current state matters
  kStatus,        // Status: periodic heartbeat whose absence must be noticed
};

// Profile parameters (see docs/topics.md).
inline constexpr std::int32_t kBlockHistoryDepth = 16;      // blocks buffered per machine
inline constexpr std::int32_t kResultHistoryDepth = 32;     // results buffered per machine
inline constexpr std::int32_t kMaxMachinesPerDomain = 256;  // instance bound for resource limits
inline constexpr std::chrono::seconds kMaxBlockingTime{1};
inline constexpr std::chrono::seconds kStatusPeriod{1};
inline constexpr std::chrono::seconds kStatusDeadline{3};

Qos TopicQos(TopicClass topic_class);
Qos WriterQos(TopicClass topic_class);
Qos ReaderQos(TopicClass topic_class);

}  // namespace gearpath::dds
