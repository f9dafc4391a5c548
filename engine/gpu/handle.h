// scansurf gpu: a move-only owner for any Vulkan handle, so every object is released by RAII.
#pragma once

#include <functional>
#include <utility>

namespace scansurf::gpu {

template <typename T>
class Owned {
 public:
  Owned() = default;
  Owned(T handle, std::function<void(T)> destroy) : handle_(handle), destroy_(std::move(destroy)) {}
  Owned(Owned&& other) noexcept : handle_(std::exchange(other.handle_, T{})), destroy_(std::move(other.destroy_)) {}
  Owned& operator=(Owned&& other) noexcept {
    if (this != &other) {
      reset();
      handle_ = std::exchange(other.handle_, T{});
      destroy_ = std::move(other.destroy_);
    }
    return *this;
  }
  Owned(const Owned&) = delete;
  Owned& operator=(const Owned&) = delete;
  ~Owned() { reset(); }

  void reset() {
    if (handle_ != T{} && destroy_) destroy_(handle_);
    handle_ = T{};
  }
  T get() const { return handle_; }
  explicit operator bool() const { return handle_ != T{}; }

 private:
  T handle_{};
  std::function<void(T)> destroy_;
};

}  // namespace scansurf::gpu
