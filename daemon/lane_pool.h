// LanePool: work queued per lane (one lane per machine) and served by a pool of worker
// threads. Items of one lane are handled one at a time, in the order they were offered; lanes
// are handled in parallel, each worker taking the next ready lane in turn (round robin, so a
// busy machine cannot starve the others).
//
// Offer never blocks: it returns false when the lane holds `capacity` items, and the producer
// (the DDS reader) then waits for room with WaitForRoom (gearpathd drops only on stop). Handled items come back as spares
// (TakeSpare), so buffers circulate instead of being allocated per block; the ready queue is a
// fixed ring. Nothing is allocated per item once the buffers exist.
//
// Pause() waits for the handlers in flight and holds the workers off until Resume(): lanes can
// then be added, detached and their owners' state changed (a reload) with no handler running.
// Thread-safe; one mutex guards every queue (each operation is O(1), blocks arrive at tens per
// second, so it is never contended for long).
#pragma once

#include <condition_variable>
#include <cstddef>
#include <functional>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

namespace gearpath::daemon {

template <typename Item>
class LanePool {
 public:
  // A lane's queue. Derive from it to carry the lane's own data (the handler gets it back).
  class Lane {
   public:
    explicit Lane(std::size_t capacity) : ring_(capacity == 0 ? 1 : capacity) {}
    virtual ~Lane() = default;
    Lane(const Lane&) = delete;
    Lane& operator=(const Lane&) = delete;

   private:
    friend class LanePool;
    std::vector<Item> ring_;
    std::size_t head_ = 0;
    std::size_t size_ = 0;
    bool scheduled_ = false;  // in the ready ring or being handled: never two workers at once
    bool attached_ = false;
  };

  // handler(worker index, lane, item): runs on a worker thread, never on two threads for the
  // same lane at once. Workers start at once.
  using Handler = std::function<void(std::size_t, Lane&, Item&)>;
  LanePool(std::size_t workers, std::size_t max_spares, Handler handler)
      : handler_(std::move(handler)), max_spares_(max_spares) {
    spares_.reserve(max_spares_);
    for (std::size_t w = 0; w < (workers == 0 ? 1 : workers); ++w) {
      threads_.emplace_back([this, w] { Work(w); });
    }
  }
  ~LanePool() { Stop(); }
  LanePool(const LanePool&) = delete;
  LanePool& operator=(const LanePool&) = delete;

  std::size_t workers() const noexcept { return threads_.size(); }

  // Makes `lane` known; at most `lanes` lanes may be attached at once (sizes the ready ring).
  // Call while paused (or before any Offer). The lane must outlive the pool or be detached
  // while paused: a worker still reads it after its handler returns.
  void Attach(Lane& lane, std::size_t lanes) {
    std::lock_guard lock(mutex_);
    if (ready_.size() < lanes) Regrow(lanes);
    lane.attached_ = true;
  }

  // Forgets `lane` (call while paused): its queued items become spares; returns their count.
  std::size_t Detach(Lane& lane) {
    std::lock_guard lock(mutex_);
    std::size_t dropped = 0;
    std::size_t kept = 0;  // the ring without `lane`, in order
    for (std::size_t i = 0; i < ready_count_; ++i) {
      Lane* at = ready_[(ready_head_ + i) % ready_.size()];
      if (at != &lane) ready_[(ready_head_ + kept++) % ready_.size()] = at;
    }
    ready_count_ = kept;
    while (lane.size_ > 0) {
      Recycle(std::move(lane.ring_[lane.head_]));
      lane.head_ = (lane.head_ + 1) % lane.ring_.size();
      --lane.size_;
      ++dropped;
    }
    lane.scheduled_ = false;
    lane.attached_ = false;
    return dropped;
  }

  // Queues `item` on `lane` (moved from) and wakes a worker; false when the lane is full, and
  // then `item` is untouched.
  bool Offer(Lane& lane, Item& item) {
    {
      std::lock_guard lock(mutex_);
      if (!lane.attached_ || lane.size_ == lane.ring_.size()) return false;
      lane.ring_[(lane.head_ + lane.size_) % lane.ring_.size()] = std::move(item);
      ++lane.size_;
      if (lane.scheduled_) return true;  // its worker, or its place in the ring, takes it
      lane.scheduled_ = true;
      PushReady(&lane);
    }
    work_ready_.notify_one();
    return true;
  }

  // Waits up to `timeout` for `lane` to have room (a worker took one of its items), or for the
  // pool to stop or the lane to be detached; true when there is room.
  template <class Duration>
  bool WaitForRoom(Lane& lane, Duration timeout) {
    std::unique_lock lock(mutex_);
    room_.wait_for(lock, timeout,
                   [&] { return stopping_ || !lane.attached_ || lane.size_ < lane.ring_.size(); });
    return lane.attached_ && lane.size_ < lane.ring_.size();
  }

  // Moves a handled item's buffers into `out` when there is one (else leaves `out` as it is).
  void TakeSpare(Item& out) {
    std::lock_guard lock(mutex_);
    if (spares_.empty()) return;
    out = std::move(spares_.back());
    spares_.pop_back();
  }

  // Waits until no handler runs and keeps workers from starting one until Resume().
  void Pause() {
    std::unique_lock lock(mutex_);
    paused_ = true;
    idle_.wait(lock, [this] { return in_flight_ == 0; });
  }
  void Resume() {
    {
      std::lock_guard lock(mutex_);
      paused_ = false;
    }
    work_ready_.notify_all();
  }

  // Lets the handlers in flight finish and joins the workers; queued items are not handled.
  void Stop() {
    {
      std::lock_guard lock(mutex_);
      stopping_ = true;
    }
    work_ready_.notify_all();
    room_.notify_all();
    for (auto& t : threads_) t.join();
    threads_.clear();
  }

 private:
  void Regrow(std::size_t lanes) {  // under mutex_: keeps the ready lanes in order
    std::vector<Lane*> grown(lanes, nullptr);
    for (std::size_t i = 0; i < ready_count_; ++i) {
      grown[i] = ready_[(ready_head_ + i) % ready_.size()];
    }
    ready_ = std::move(grown);
    ready_head_ = 0;
  }
  void PushReady(Lane* lane) {  // under mutex_; a lane is in the ring at most once
    ready_[(ready_head_ + ready_count_) % ready_.size()] = lane;
    ++ready_count_;
  }
  void Recycle(Item&& item) {  // under mutex_; beyond max_spares_ the buffers are freed
    if (spares_.size() < max_spares_) spares_.push_back(std::move(item));
  }

  void Work(std::size_t worker) {
    Item current{};
    std::unique_lock lock(mutex_);
    for (;;) {
      work_ready_.wait(lock, [this] { return stopping_ || (!paused_ && ready_count_ > 0); });
      if (stopping_) return;
      Lane* lane = ready_[ready_head_];
      ready_head_ = (ready_head_ + 1) % ready_.size();
      --ready_count_;
      current = std::move(lane->ring_[lane->head_]);
      lane->head_ = (lane->head_ + 1) % lane->ring_.size();
      --lane->size_;
      ++in_flight_;
      lock.unlock();
      room_.notify_all();
      handler_(worker, *lane, current);
      lock.lock();
      --in_flight_;
      Recycle(std::move(current));
      current = Item{};
      if (lane->size_ > 0) {
        PushReady(lane);  // back of the ring: the other ready lanes go first
        work_ready_.notify_one();
      } else {
        lane->scheduled_ = false;
      }
      if (paused_ && in_flight_ == 0) idle_.notify_all();
    }
  }

  Handler handler_;
  const std::size_t max_spares_;
  std::mutex mutex_;
  std::condition_variable work_ready_;
  std::condition_variable idle_;
  std::condition_variable room_;  // a lane's item was taken (WaitForRoom)
  std::vector<Lane*> ready_ = std::vector<Lane*>(1, nullptr);  // ring of lanes with work
  std::size_t ready_head_ = 0;
  std::size_t ready_count_ = 0;
  std::vector<Item> spares_;
  std::size_t in_flight_ = 0;
  bool paused_ = false;
  bool stopping_ = false;
  std::vector<std::thread> threads_;  // last: started once everything above exists
};

}  // namespace gearpath::daemon
