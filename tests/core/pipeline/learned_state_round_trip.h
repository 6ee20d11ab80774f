// A learned state through the text the daemon writes and reads back (core/pipeline/
// learned_state_json.h), for the tests that resume a processor from it.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <utility>

#include "core/pipeline/learned_state_json.h"

namespace gearpath::testing {

inline LearnedState ThroughJson(const LearnedState& s) {
  // Text, not the json object: what the daemon writes and reads back.
  const std::string text = ToJson(s).dump();
  auto back = LearnedStateFromJson(nlohmann::json::parse(text));
  EXPECT_TRUE(back.ok()) << back.error();
  return back.ok() ? std::move(back.value()) : LearnedState{};
}

}  // namespace gearpath::testing
