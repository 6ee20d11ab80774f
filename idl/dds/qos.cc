#include "idl/dds/qos.h"

#include <new>
#include <utility>

namespace gearpath::dds {

namespace {

dds_qos_t* CreateQos() {
  dds_qos_t* qos = dds_create_qos();
  if (qos == nullptr) throw std::bad_alloc();
  return qos;
}

dds_duration_t ToDuration(std::chrono::nanoseconds d) noexcept {
  return static_cast<dds_duration_t>(d.count());
}

}  // namespace

Qos::Qos() : qos_(CreateQos()) {}

Qos::~Qos() {
  if (qos_ != nullptr) dds_delete_qos(qos_);
}

Qos::Qos(const Qos& other) : qos_(CreateQos()) { dds_copy_qos(qos_, other.qos_); }

Qos& Qos::operator=(const Qos& other) {
  if (this != &other) {
    Qos copy(other);
    std::swap(qos_, copy.qos_);
  }
  return *this;
}

Qos::Qos(Qos&& other) noexcept : qos_(std::exchange(other.qos_, nullptr)) {}

Qos& Qos::operator=(Qos&& other) noexcept {
  std::swap(qos_, other.qos_);
  return *this;
}

Qos& Qos::Reliable(std::chrono::nanoseconds max_blocking_time) {
  dds_qset_reliability(qos_, DDS_RELIABILITY_RELIABLE, ToDuration(max_blocking_time));
  return *this;
}

Qos& Qos::BestEffort() {
  dds_qset_reliability(qos_, DDS_RELIABILITY_BEST_EFFORT, 0);
  return *this;
}

Qos& Qos::KeepLast(std::int32_t depth) {
  dds_qset_history(qos_, DDS_HISTORY_KEEP_LAST, depth);
  return *this;
}

Qos& Qos::KeepAll() {
  dds_qset_history(qos_, DDS_HISTORY_KEEP_ALL, DDS_LENGTH_UNLIMITED);
  return *this;
}

Qos& Qos::Volatile() {
  dds_qset_durability(qos_, DDS_DURABILITY_VOLATILE);
  return *this;
}

Qos& Qos::TransientLocal() {
  dds_qset_durability(qos_, DDS_DURABILITY_TRANSIENT_LOCAL);
  return *this;
}

Qos& Qos::DurabilityServiceKeepLast(std::int32_t depth) {
  dds_qset_durability_service(qos_, 0, DDS_HISTORY_KEEP_LAST, depth, DDS_LENGTH_UNLIMITED,
                              DDS_LENGTH_UNLIMITED, DDS_LENGTH_UNLIMITED);
  return *this;
}

Qos& Qos::ResourceLimits(std::int32_t max_samples, std::int32_t max_instances,
                         std::int32_t max_samples_per_instance) {
  dds_qset_resource_limits(qos_, max_samples, max_instances, max_samples_per_instance);
  return *this;
}

Qos& Qos::Deadline(std::chrono::nanoseconds period) {
  dds_qset_deadline(qos_, ToDuration(period));
  return *this;
}

Qos& Qos::LivelinessAutomatic(std::chrono::nanoseconds lease_duration) {
  dds_qset_liveliness(qos_, DDS_LIVELINESS_AUTOMATIC, ToDuration(lease_duration));
  return *this;
}

namespace {

// What writer and reader of a class share (they must match for the endpoints to connect).
Qos CommonQos(TopicClass topic_class) {
  Qos qos;
  qos.Reliable(kMaxBlockingTime);
  switch (topic_class) {
    case TopicClass::kBlockStream:
      // Volatile: a block is only worth processing when it arrives; a late daemon starts with
      // the next block rather than a replay.
      qos.Volatile().KeepAll().ResourceLimits(kBlockHistoryDepth * kMaxMachinesPerDomain,
                                              kMaxMachinesPerDomain, kBlockHistoryDepth);
      break;
    case TopicClass::kLatestResult:
      // Keep-last kResultHistoryDepth: a reliable subscriber that falls behind for a moment
      // (a loaded host) still receives every block's result; late joiners get only the latest
      // (durability-service depth 1).
      qos.TransientLocal().KeepLast(kResultHistoryDepth).DurabilityServiceKeepLast(1);
      break;
    case TopicClass::kStatus:
      qos.TransientLocal().KeepLast(1).DurabilityServiceKeepLast(1).Deadline(kStatusDeadline);
      break;
  }
  return qos;
}

}  // namespace

Qos TopicQos(TopicClass topic_class) { return CommonQos(topic_class); }
Qos WriterQos(TopicClass topic_class) { return CommonQos(topic_class); }
Qos ReaderQos(TopicClass topic_class) { return CommonQos(topic_class); }

}  // namespace gearpath::dds
