// BlockSink: where a feeding tool puts its AccelBlocks. BlockPublisher (DDS) is the real one;
// the bridge's tests substitute an in-memory sink so that most of them need no DDS.
#pragma once

#include <chrono>

#include "core/common/accel_block.h"
#include "core/common/result.h"

namespace gearpath::tools {

class BlockSink {
 public:
  virtual ~BlockSink() = default;
  // Ok once the block is delivered (for DDS: written, and acknowledged when asked for); an
  // error leaves the block undelivered, so the caller must not count it as sent.
  virtual Status Publish(const AccelBlockView& block) = 0;
  // Waits until everything published so far has been taken.
  virtual Status Flush(std::chrono::milliseconds timeout) = 0;
};

}  // namespace gearpath::tools
