// C++ views of idlc's C sequences and bounded strings, so daemon/ and tools/ never juggle
// _buffer/_length/_maximum/_release by hand.
//
// An idlc sequence is {_maximum, _length, _buffer, _release}. The functions here keep it in
// the one state Owned<T> and Reader<T>::Take rely on: _buffer allocated with dds_alloc (so
// dds_sample_free can release it), _release = true (the sample owns it), _maximum = capacity.
// Resize grows the buffer only when needed, so a sample reused block after block stops
// allocating once it has reached its size. Elements must be flat (no pointers inside), which
// holds for every gearpath element type (they hold bounded strings as char arrays).
//
// Bounded IDL strings (string<N>) are char[N + 1] arrays in C; SetString refuses a value that
// does not fit rather than truncating an identifier.
#pragma once

#include <dds/dds.h>

#include <cstdint>
#include <cstring>
#include <span>
#include <string_view>
#include <type_traits>

namespace gearpath::dds {

template <typename Seq>
using SequenceElement = std::remove_pointer_t<decltype(Seq{}._buffer)>;

// Read-only view of the sequence's current elements.
template <typename Seq>
std::span<const SequenceElement<Seq>> View(const Seq& seq) noexcept {
  return {seq._buffer, seq._length};
}

// Writable view of the sequence's current elements (to fill in place after Resize).
template <typename Seq>
std::span<SequenceElement<Seq>> MutableView(Seq& seq) noexcept {
  return {seq._buffer, seq._length};
}

// Sets the length to `length`, growing the capacity if needed; new elements are zeroed.
// Returns false (sequence unchanged) if the allocation fails or the sequence does not own its
// buffer (_release false with a buffer: memory this layer must not reallocate).
template <typename Seq>
[[nodiscard]] bool Resize(Seq& seq, std::uint32_t length) noexcept {
  using Element = SequenceElement<Seq>;
  static_assert(std::is_trivially_copyable_v<Element>, "sequence elements must be flat");
  if (length > seq._maximum) {
    if (seq._buffer != nullptr && !seq._release) return false;
    void* grown = dds_realloc(seq._buffer, std::size_t{length} * sizeof(Element));
    if (grown == nullptr) return false;
    seq._buffer = static_cast<Element*>(grown);
    std::memset(static_cast<void*>(seq._buffer + seq._maximum), 0,
                std::size_t{length - seq._maximum} * sizeof(Element));
    seq._maximum = length;
    seq._release = true;
  }
  seq._length = length;
  return true;
}

// Replaces the contents with a copy of `values`. Returns false as Resize does.
template <typename Seq>
[[nodiscard]] bool Assign(Seq& seq, std::span<const SequenceElement<Seq>> values) noexcept {
  if (values.size() > UINT32_MAX) return false;
  if (!Resize(seq, static_cast<std::uint32_t>(values.size()))) return false;
  if (!values.empty()) {
    std::memcpy(static_cast<void*>(seq._buffer), values.data(), values.size_bytes());
  }
  return true;
}

// Copies `value` into a bounded string; false (and `dst` unchanged) if it does not fit or
// contains a NUL.
template <std::size_t N>
[[nodiscard]] bool SetString(char (&dst)[N], std::string_view value) noexcept {
  if (value.size() >= N || value.find('\0') != std::string_view::npos) return false;
  std::memcpy(dst, value.data(), value.size());
  dst[value.size()] = '\0';
  return true;
}

template <std::size_t N>
std::string_view GetString(const char (&src)[N]) noexcept {
  return {src, strnlen(src, N)};
}

}  // namespace gearpath::dds
