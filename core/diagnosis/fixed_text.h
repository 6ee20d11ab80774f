// FixedText: a short message in a fixed-size buffer, for reasons and rejection messages
// produced on the per-block hot path, where formatting into a std::string would allocate.
// Text longer than the capacity is truncated (never overflows); the capacity is sized for
// one-line messages that name the expected and the received value.
#pragma once

#include <array>
#include <cstdarg>
#include <cstddef>
#include <cstdio>
#include <string_view>

namespace gearpath {

template <std::size_t N>
class FixedText {
 public:
  FixedText() noexcept { buf_[0] = '\0'; }

  // printf-style formatting (no allocation); truncates at N - 1 characters.
  [[gnu::format(printf, 2, 3)]] void Format(const char* format, ...) noexcept {
    va_list args;
    va_start(args, format);
    const int n = std::vsnprintf(buf_.data(), N, format, args);
    va_end(args);
    len_ = n < 0 ? 0 : (static_cast<std::size_t>(n) < N ? static_cast<std::size_t>(n) : N - 1);
  }
  void Assign(std::string_view text) noexcept {
    len_ = text.size() < N ? text.size() : N - 1;
    for (std::size_t i = 0; i < len_; ++i) buf_[i] = text[i];
    buf_[len_] = '\0';
  }
  void Clear() noexcept {
    len_ = 0;
    buf_[0] = '\0';
  }

  std::string_view view() const noexcept { return {buf_.data(), len_}; }
  const char* c_str() const noexcept { return buf_.data(); }
  bool empty() const noexcept { return len_ == 0; }

 private:
  std::array<char, N> buf_{};
  std::size_t len_ = 0;
};

// The size used for every per-block message in gearpath (fits a DDS bounded string<256>).
using MessageText = FixedText<256>;

}  // namespace gearpath
