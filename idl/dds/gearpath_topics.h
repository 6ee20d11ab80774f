// The gearpath topics: TopicTraits for the idlc types of idl/gearpath.idl, binding each to its
// topic name and QoS class (docs/topics.md is the reference for both).
//
// Names follow "gearpath/<Type>". Include this header (it includes every other header of the
// layer) to use Topic<gearpath_AccelBlock> and friends.
#pragma once

#include <dds/dds.h>

#include <string_view>

#include "idl/dds/domain.h"
#include "idl/dds/qos.h"
#include "idl/dds/sequence.h"
#include "idl/dds/topic.h"
#include "idl/dds/waitset.h"
#include "idl/gearpath.h"

namespace gearpath::dds {

template <>
struct TopicTraits<gearpath_AccelBlock> {
  static const dds_topic_descriptor_t& Descriptor() noexcept { return gearpath_AccelBlock_desc; }
  static constexpr std::string_view kName = "gearpath/AccelBlock";
  static constexpr TopicClass kClass = TopicClass::kBlockStream;
};

template <>
struct TopicTraits<gearpath_AccelBlockV2> {
  static const dds_topic_descriptor_t& Descriptor() noexcept { return gearpath_AccelBlockV2_desc; }
  static constexpr std::string_view kName = "gearpath/AccelBlockV2";
  static constexpr TopicClass kClass = TopicClass::kBlockStream;
};

template <>
struct TopicTraits<gearpath_DominantPath> {
  static const dds_topic_descriptor_t& Descriptor() noexcept { return gearpath_DominantPath_desc; }
  static constexpr std::string_view kName = "gearpath/DominantPath";
  static constexpr TopicClass kClass = TopicClass::kLatestResult;
};

template <>
struct TopicTraits<gearpath_SuspectedGear> {
  static const dds_topic_descriptor_t& Descriptor() noexcept { return gearpath_SuspectedGear_desc; }
  static constexpr std::string_view kName = "gearpath/SuspectedGear";
  static constexpr TopicClass kClass = TopicClass::kLatestResult;
};

template <>
struct TopicTraits<gearpath_EnvelopeIndicators> {
  static const dds_topic_descriptor_t& Descriptor() noexcept {
    return gearpath_EnvelopeIndicators_desc;
  }
  static constexpr std::string_view kName = "gearpath/EnvelopeIndicators";
  static constexpr TopicClass kClass = TopicClass::kLatestResult;
};

template <>
struct TopicTraits<gearpath_ConditionIndicators> {
  static const dds_topic_descriptor_t& Descriptor() noexcept {
    return gearpath_ConditionIndicators_desc;
  }
  static constexpr std::string_view kName = "gearpath/ConditionIndicators";
  static constexpr TopicClass kClass = TopicClass::kLatestResult;
};

template <>
struct TopicTraits<gearpath_Status> {
  static const dds_topic_descriptor_t& Descriptor() noexcept { return gearpath_Status_desc; }
  static constexpr std::string_view kName = "gearpath/Status";
  static constexpr TopicClass kClass = TopicClass::kStatus;
};

// One instance per (daemon, machine), published every status period: the status class (its
// deadline tells a subscriber that the daemon stopped reporting the machine).
template <>
struct TopicTraits<gearpath_MachineHealth> {
  static const dds_topic_descriptor_t& Descriptor() noexcept {
    return gearpath_MachineHealth_desc;
  }
  static constexpr std::string_view kName = "gearpath/MachineHealth";
  static constexpr TopicClass kClass = TopicClass::kStatus;
};

}  // namespace gearpath::dds
