// Replacement of every global allocation and deallocation function, for the tests that count
// allocations (DESIGN.md: hot paths allocate nothing). Each operator new calls
// counting_new::OnAllocation(), which the including file defines, then takes its memory from
// std::malloc (std::posix_memalign for the aligned forms); each operator delete gives it back
// with std::free. All the forms are replaced together, so every delete meets memory of the
// allocator it expects: replacing operator new alone leaves the library's delete, and
// AddressSanitizer's own operator delete reports that as alloc-dealloc-mismatch.
//
// The replacements are noinline: inlined, GCC pairs a new-expression with std::free and warns
// (-Wmismatched-new-delete) although the pair is the matching one.
//
// Include this header in exactly one source file of a test executable (the replacements are
// ordinary, non-inline definitions; a second copy does not link).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <new>

namespace counting_new {

// Called once by every operator new before it allocates; defined by the including file.
void OnAllocation() noexcept;

inline void* Allocate(std::size_t size) noexcept {
  OnAllocation();
  return std::malloc(size == 0 ? 1 : size);
}

inline void* AllocateAligned(std::size_t size, std::align_val_t alignment) noexcept {
  OnAllocation();
  void* p = nullptr;
  const std::size_t a = std::max(static_cast<std::size_t>(alignment), sizeof(void*));
  return posix_memalign(&p, a, size == 0 ? 1 : size) == 0 ? p : nullptr;
}

inline void* OrThrow(void* p) {
  if (p == nullptr) throw std::bad_alloc();
  return p;
}

}  // namespace counting_new

[[gnu::noinline]] void* operator new(std::size_t size) {
  return counting_new::OrThrow(counting_new::Allocate(size));
}
[[gnu::noinline]] void* operator new[](std::size_t size) {
  return counting_new::OrThrow(counting_new::Allocate(size));
}
[[gnu::noinline]] void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  return counting_new::Allocate(size);
}
[[gnu::noinline]] void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  return counting_new::Allocate(size);
}
[[gnu::noinline]] void* operator new(std::size_t size, std::align_val_t alignment) {
  return counting_new::OrThrow(counting_new::AllocateAligned(size, alignment));
}
[[gnu::noinline]] void* operator new[](std::size_t size, std::align_val_t alignment) {
  return counting_new::OrThrow(counting_new::AllocateAligned(size, alignment));
}
[[gnu::noinline]] void* operator new(std::size_t size, std::align_val_t alignment,
                                     const std::nothrow_t&) noexcept {
  return counting_new::AllocateAligned(size, alignment);
}
[[gnu::noinline]] void* operator new[](std::size_t size, std::align_val_t alignment,
                                       const std::nothrow_t&) noexcept {
  return counting_new::AllocateAligned(size, alignment);
}

[[gnu::noinline]] void operator delete(void* p) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete[](void* p) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete(void* p, std::size_t) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete(void* p, std::size_t, std::align_val_t) noexcept {
  std::free(p);
}
[[gnu::noinline]] void operator delete[](void* p, std::size_t, std::align_val_t) noexcept {
  std::free(p);
}
[[gnu::noinline]] void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept {
  std::free(p);
}
[[gnu::noinline]] void operator delete[](void* p, std::align_val_t,
                                         const std::nothrow_t&) noexcept {
  std::free(p);
}
