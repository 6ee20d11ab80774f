// Topic<T>, Owned<T>, Writer<T>, Reader<T>: typed DDS endpoints over idlc-generated C types.
//
// A type T is usable once TopicTraits<T> is specialised with its idlc descriptor and default
// topic name (idl/dds/gearpath_topics.h does that for the gearpath types).
//
// Sample memory. idlc's C types own heap memory through their sequences (dds_alloc'ed
// _buffer with _release = true). Owned<T> is the C++ owner of one such sample: it starts
// zeroed, frees its contents with dds_sample_free(DDS_FREE_CONTENTS) when destroyed and is
// move-only. Reader<T>::Take deserialises into caller-owned Owned<T> objects (dds_take with
// preallocated buffers, not loans): Cyclone reuses each sequence buffer when it is large enough
// and reallocates it otherwise, so a reader that takes into the same vector block after block
// allocates only while the buffers grow, and nothing is ever left to return or leak. Writer<T>
// never takes ownership: Write serialises and returns.
//
// Threads. Cyclone entity calls are thread-safe, but a Reader keeps a scratch pointer array for
// Take, so one Reader object is used by one thread at a time. Do not call these from a Cyclone
// listener (listeners run on Cyclone's threads; use a WaitSet in your own thread).
#pragma once

#include <dds/dds.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/common/result.h"
#include "idl/dds/domain.h"
#include "idl/dds/entity.h"
#include "idl/dds/error.h"
#include "idl/dds/qos.h"

namespace gearpath::dds {

// Specialise for each topic type:
//   static const dds_topic_descriptor_t& Descriptor();
//   static constexpr std::string_view kName;        // default topic name
//   static constexpr TopicClass kClass;            // QoS profile
template <typename T>
struct TopicTraits;

using SampleInfo = dds_sample_info_t;

template <typename T>
class Owned {
 public:
  Owned() noexcept : value_{} {}
  ~Owned() { Release(); }
  Owned(const Owned&) = delete;
  Owned& operator=(const Owned&) = delete;
  // A C sample moves bitwise: the pointers change owner and the source is left zeroed.
  Owned(Owned&& other) noexcept : value_(std::exchange(other.value_, T{})) {}
  Owned& operator=(Owned&& other) noexcept {
    if (this != &other) {
      Release();
      value_ = std::exchange(other.value_, T{});
    }
    return *this;
  }

  T& get() noexcept { return value_; }
  const T& get() const noexcept { return value_; }
  T* operator->() noexcept { return &value_; }
  const T* operator->() const noexcept { return &value_; }
  T& operator*() noexcept { return value_; }
  const T& operator*() const noexcept { return value_; }

 private:
  void Release() noexcept {
    dds_sample_free(&value_, &TopicTraits<T>::Descriptor(), DDS_FREE_CONTENTS);
    value_ = T{};
  }

  T value_;
};

template <typename T>
class Topic : public Entity {
 public:
  // Throws std::runtime_error naming dds_create_topic and the topic name on failure.
  explicit Topic(const Participant& participant, std::string_view name = TopicTraits<T>::kName,
                 const Qos& qos = TopicQos(TopicTraits<T>::kClass))
      : Topic(participant, std::string(name), qos) {}

  const std::string& name() const noexcept { return name_; }
  dds_entity_t participant_handle() const noexcept { return participant_; }

  // Drops samples for which `accept(sample, arg)` is false before they reach any reader of
  // this topic entity: they take no place in a reader's history or instance limits, and are
  // acknowledged, so their writer is not held up. Cyclone calls `accept` on its receive
  // threads. Set it before creating the readers, on a topic entity that only they use.
  void SetSampleFilter(bool (*accept)(const void* sample, void* arg), void* arg) {
    dds_topic_filter filter{};
    filter.mode = DDS_TOPIC_FILTER_SAMPLE_ARG;
    filter.f.sample_arg = accept;
    filter.arg = arg;
    CheckDds(dds_set_topic_filter_extended(handle(), &filter),
             "dds_set_topic_filter_extended(\"" + name_ + "\")");
  }

 private:
  Topic(const Participant& participant, std::string name, const Qos& qos)
      : Entity(CheckDds(dds_create_topic(participant.handle(), &TopicTraits<T>::Descriptor(),
                                         name.c_str(), qos.get(), nullptr),
                        "dds_create_topic(\"" + name + "\")"),
               participant.node()),
        name_(std::move(name)),
        participant_(participant.handle()) {}

  std::string name_;
  dds_entity_t participant_;
};

template <typename T>
class Writer : public Entity {
 public:
  // Throws std::runtime_error naming dds_create_writer and the topic on failure (for example an
  // inconsistent QoS).
  explicit Writer(const Topic<T>& topic, const Qos& qos = WriterQos(TopicTraits<T>::kClass))
      : Entity(CheckDds(dds_create_writer(topic.participant_handle(), topic.handle(), qos.get(),
                                          nullptr),
                        "dds_create_writer(\"" + topic.name() + "\")"),
               topic.node()),
        topic_name_(topic.name()) {}

  // Publishes one sample. With a reliable keep-all QoS this blocks while the readers'
  // acknowledgements lag (flow control) and fails with "Timeout" after the QoS's
  // max_blocking_time. A sequence above its IDL bound fails with "Bad Parameter".
  Status Write(const T& sample) noexcept {
    const dds_return_t rc = dds_write(handle(), &sample);
    if (rc < 0) return Error{DdsErrorMessage("dds_write(\"" + topic_name_ + "\")", rc)};
    return Status::Ok();
  }

  // Disposes the instance whose key fields `key_sample` carries (the other fields are
  // ignored): readers see it NOT_ALIVE_DISPOSED, and a transient-local writer no longer
  // hands its last sample to late joiners.
  Status Dispose(const T& key_sample) noexcept {
    const dds_return_t rc = dds_dispose(handle(), &key_sample);
    if (rc < 0) return Error{DdsErrorMessage("dds_dispose(\"" + topic_name_ + "\")", rc)};
    return Status::Ok();
  }

  // Number of readers currently matched (discovery is asynchronous).
  Result<std::uint32_t> MatchedReaders() const noexcept {
    dds_publication_matched_status_t status{};
    const dds_return_t rc = dds_get_publication_matched_status(handle(), &status);
    if (rc < 0) return Error{DdsErrorMessage("dds_get_publication_matched_status", rc)};
    return status.current_count;
  }

  // Polls until at least `count` readers are matched or `timeout` passes.
  Status WaitForReaders(std::uint32_t count, std::chrono::nanoseconds timeout) const noexcept {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    for (;;) {
      Result<std::uint32_t> matched = MatchedReaders();
      if (!matched) return Error{matched.error()};
      if (*matched >= count) return Status::Ok();
      if (std::chrono::steady_clock::now() >= deadline) {
        return Error{"Writer(\"" + topic_name_ + "\"): " + std::to_string(*matched) + " of " +
                     std::to_string(count) + " readers matched before the timeout"};
      }
      dds_sleepfor(DDS_MSECS(5));
    }
  }

 private:
  std::string topic_name_;
};

template <typename T>
class Reader : public Entity {
 public:
  // Throws std::runtime_error naming dds_create_reader and the topic on failure.
  explicit Reader(const Topic<T>& topic, const Qos& qos = ReaderQos(TopicTraits<T>::kClass))
      : Entity(CheckDds(dds_create_reader(topic.participant_handle(), topic.handle(), qos.get(),
                                          nullptr),
                        "dds_create_reader(\"" + topic.name() + "\")"),
               topic.node()),
        topic_name_(topic.name()) {}

  // Takes up to min(samples.size(), infos.size()) samples, oldest first, into the caller's
  // samples (reusing their memory) and returns how many were taken. Samples whose
  // infos[i].valid_data is false carry only the key (an instance state change: disposed or
  // no writers). Allocation-free once the scratch array and the sample buffers have grown.
  Result<std::size_t> Take(std::span<Owned<T>> samples, std::span<SampleInfo> infos) noexcept {
    return Fetch(handle(), samples, infos, /*take=*/true);
  }

  // Same as Take but leaves the samples in the reader's history (marked read).
  Result<std::size_t> Read(std::span<Owned<T>> samples, std::span<SampleInfo> infos) noexcept {
    return Fetch(handle(), samples, infos, /*take=*/false);
  }

  // Takes only samples matching `condition` (a ReadCondition created on this reader).
  Result<std::size_t> Take(const Entity& condition, std::span<Owned<T>> samples,
                           std::span<SampleInfo> infos) noexcept {
    return Fetch(condition.handle(), samples, infos, /*take=*/true);
  }

 private:
  Result<std::size_t> Fetch(dds_entity_t from, std::span<Owned<T>> samples,
                            std::span<SampleInfo> infos, bool take) noexcept {
    const std::size_t n = std::min(
        {samples.size(), infos.size(), std::size_t{std::numeric_limits<std::uint32_t>::max()}});
    if (n == 0) return std::size_t{0};
    if (scratch_.size() < n) {
      try {
        scratch_.resize(n);
      } catch (...) {
        return Error{"Reader(\"" + topic_name_ + "\"): out of memory for " + std::to_string(n) +
                     " sample pointers"};
      }
    }
    for (std::size_t i = 0; i < n; ++i) scratch_[i] = &samples[i].get();
    const auto max = static_cast<std::uint32_t>(n);
    const dds_return_t rc = take ? dds_take(from, scratch_.data(), infos.data(), n, max)
                                 : dds_read(from, scratch_.data(), infos.data(), n, max);
    if (rc < 0) {
      return Error{DdsErrorMessage(
          std::string(take ? "dds_take" : "dds_read") + "(\"" + topic_name_ + "\")", rc)};
    }
    return static_cast<std::size_t>(rc);
  }

  std::string topic_name_;
  std::vector<void*> scratch_;
};

}  // namespace gearpath::dds
