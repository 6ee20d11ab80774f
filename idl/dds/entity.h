// Entity: shared ownership of one Cyclone DDS entity handle, the base of every RAII class here.
//
// Cyclone's C API hands out integer handles in a tree (domain > participant > topic > reader/
// writer/condition; waitset under participant). Each wrapper owns a node that deletes its
// handle when the last reference goes, and each node holds a reference to its parent's node, so
// whatever order the wrappers are destroyed in, dds_delete runs on the child first, then on the
// parent. The wrapper
// objects are move-only (one owner in user code); the shared node is an implementation detail
// that exists only to keep parents alive. A moved-from wrapper holds no entity (handle() == 0)
// and may only be destroyed or assigned to.
#pragma once

#include <dds/dds.h>

#include <memory>
#include <utility>

namespace gearpath::dds {

namespace detail {

class EntityNode {
 public:
  EntityNode(dds_entity_t handle, std::shared_ptr<const EntityNode> parent) noexcept
      : handle_(handle), parent_(std::move(parent)) {}
  // Deletes the entity (and anything Cyclone still has under it), then releases the parent.
  // The return code is ignored on purpose: the entity may already be gone because a test or a
  // shutdown path deleted it through the C API, and a destructor has no one to report to.
  ~EntityNode() { (void)dds_delete(handle_); }
  EntityNode(const EntityNode&) = delete;
  EntityNode& operator=(const EntityNode&) = delete;

  dds_entity_t handle() const noexcept { return handle_; }

 private:
  dds_entity_t handle_;
  std::shared_ptr<const EntityNode> parent_;
};

}  // namespace detail

class Entity {
 public:
  Entity(const Entity&) = delete;
  Entity& operator=(const Entity&) = delete;
  Entity(Entity&&) noexcept = default;
  Entity& operator=(Entity&&) noexcept = default;

  // The raw handle, for calls this layer does not wrap. Do not dds_delete it.
  dds_entity_t handle() const noexcept { return node_ ? node_->handle() : 0; }
  // The ownership node; a child passes it as its parent.
  const std::shared_ptr<const detail::EntityNode>& node() const noexcept { return node_; }

 protected:
  // Takes ownership of `handle` (> 0; callers check with CheckDds first).
  // If allocating the node fails, the handle is deleted before the exception propagates.
  Entity(dds_entity_t handle, std::shared_ptr<const detail::EntityNode> parent)
      : node_(MakeNode(handle, std::move(parent))) {}
  ~Entity() = default;

 private:
  static std::shared_ptr<const detail::EntityNode> MakeNode(
      dds_entity_t handle, std::shared_ptr<const detail::EntityNode> parent) {
    try {
      return std::make_shared<const detail::EntityNode>(handle, std::move(parent));
    } catch (...) {
      (void)dds_delete(handle);
      throw;
    }
  }

  std::shared_ptr<const detail::EntityNode> node_;
};

}  // namespace gearpath::dds
