#pragma once
// GrowOnlyArray<T>: an array for a backend's large per-frame tables (recorded boxes, binned
// items, transformed vertices) that grows in place and never gives memory back. It lives in
// address space reserved once (16 GiB, none of it memory until used) and asked for transparent
// huge pages: growing never moves or copies it, clear() keeps what it has touched, and its pages
// fault once, 2 MiB at a time where the kernel gives huge pages.
//
// Why: on a virtual machine a page fault can cost far more than the work that touches the page
// (measured on the project's 2-core VM: 10.7 us per 4 KiB page touched first, against 0.3 us per
// 4 KiB of a reused 2 MiB page; docs/cpu-backend-history.md). A std::vector that doubles copies
// into fresh pages and frees the old ones, so the frames where a scene grows paid for its tables'
// pages two or three times over.
//
// 16 GiB holds any table of this project many times over (the largest, a recording's boxes at 120
// bytes each in `cullide_bvh` on env2, reaches 14 MB) and leaves room for thousands of arrays at
// once in a process' 128 TiB of address space; an array asked for more throws std::length_error.
//
// Elements are constructed by push_back/emplace_back/append, or default-initialised by resize
// (a type without initialisers is left as the memory holds it, to be written before it is read),
// and never destroyed (T is trivially destructible). Where the reservation is refused, and in
// sanitizer builds (whose checks need the heap), it grows as a vector does.
#include <sys/mman.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <memory>
#include <new>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "core/AddressSanitizer.h"

namespace cdb {

// AddressSanitizer checks heap blocks, not reserved address space: in its builds the arrays grow
// on the heap.
inline constexpr bool kGrowOnlyArrayOnHeap = kAddressSanitizer;

template <class T>
class GrowOnlyArray {
  static_assert(std::is_trivially_destructible_v<T>, "elements are never destroyed");

 public:
  using value_type = T;
  using iterator = T*;
  using const_iterator = const T*;

  // Address space reserved per array, and the step it is made usable in (a huge page).
  static constexpr std::size_t kReservedBytes = std::size_t{16} << 30;
  static constexpr std::size_t kStepBytes = std::size_t{2} << 20;

  GrowOnlyArray() = default;
  GrowOnlyArray(const GrowOnlyArray&) = delete;
  GrowOnlyArray& operator=(const GrowOnlyArray&) = delete;
  GrowOnlyArray(GrowOnlyArray&& other) noexcept { take(other); }
  GrowOnlyArray& operator=(GrowOnlyArray&& other) noexcept {
    if (this != &other) {
      release();
      take(other);
    }
    return *this;
  }
  ~GrowOnlyArray() { release(); }

  [[nodiscard]] std::size_t size() const { return size_; }
  [[nodiscard]] bool empty() const { return size_ == 0; }
  [[nodiscard]] std::size_t capacity() const { return capacity_; }
  [[nodiscard]] T* data() { return data_; }
  [[nodiscard]] const T* data() const { return data_; }
  [[nodiscard]] T& operator[](std::size_t i) { return data_[i]; }
  [[nodiscard]] const T& operator[](std::size_t i) const { return data_[i]; }
  [[nodiscard]] T* begin() { return data_; }
  [[nodiscard]] T* end() { return data_ + size_; }
  [[nodiscard]] const T* begin() const { return data_; }
  [[nodiscard]] const T* end() const { return data_ + size_; }
  [[nodiscard]] T& back() { return data_[size_ - 1]; }
  [[nodiscard]] const T& back() const { return data_[size_ - 1]; }

  // No elements; the memory stays, for the next frame's.
  void clear() { size_ = 0; }
  // `n` elements, those added left unwritten (as std::make_unique_for_overwrite): for a caller
  // that writes them before it reads them. (T is trivially copyable: its objects begin to exist
  // in the storage.)
  void resizeForOverwrite(std::size_t n) {
    static_assert(std::is_trivially_copyable_v<T>, "elements that need no construction");
    makeRoom(n);
    size_ = n;
  }
  // `n` elements: those added default-initialised.
  void resize(std::size_t n) {
    if (n > size_) {
      makeRoom(n);
      std::uninitialized_default_construct(data_ + size_, data_ + n);
    }
    size_ = n;
  }
  void push_back(const T& value) {
    makeRoom(size_ + 1);
    std::construct_at(data_ + size_, value);
    ++size_;
  }
  template <class... Args>
  T& emplace_back(Args&&... args) {
    makeRoom(size_ + 1);
    T* at = std::construct_at(data_ + size_, std::forward<Args>(args)...);
    ++size_;
    return *at;
  }
  // The elements [first, last) added at the end.
  template <class It>
  void append(It first, It last) {
    const auto n = static_cast<std::size_t>(std::distance(first, last));
    makeRoom(size_ + n);
    std::uninitialized_copy(first, last, data_ + size_);
    size_ += n;
  }

 private:
  static constexpr std::size_t wholeSteps(std::size_t bytes) {
    return (bytes + kStepBytes - 1) / kStepBytes * kStepBytes;
  }
  static_assert(sizeof(T) <= kStepBytes, "capacity_ elements end in the last usable step");

  void makeRoom(std::size_t n) {
    if (n > capacity_) grow(n);
  }

  void grow(std::size_t n) {
    if (n > kReservedBytes / sizeof(T)) throw std::length_error("GrowOnlyArray: too many elements");
    if (!kGrowOnlyArrayOnHeap && capacity_ == 0 && reserved_ == nullptr) reserveAddressSpace();
    if (reserved_ != nullptr) {
      // The steps past those usable already, up to the one holding n elements (the address space
      // is already there; capacity_ elements end in the last usable step).
      const std::size_t usable = wholeSteps(capacity_ * sizeof(T));
      const std::size_t bytes = wholeSteps(n * sizeof(T));
      if (::mprotect(reserved_ + usable, bytes - usable, PROT_READ | PROT_WRITE) != 0)
        throw std::bad_alloc();
      capacity_ = bytes / sizeof(T);
      return;
    }
    // As a vector: a larger block, the elements moved into it.
    const std::size_t wanted = std::max(n, 2 * capacity_);
    T* larger = static_cast<T*>(::operator new (wanted * sizeof(T), std::align_val_t{alignof(T)}));
    std::uninitialized_move(data_, data_ + size_, larger);
    freeHeapBlock();
    data_ = larger;
    capacity_ = wanted;
  }

  // The address space, aligned to a huge page (without it, or when refused, the heap is used).
  void reserveAddressSpace() {
    void* at = ::mmap(nullptr, kReservedBytes + kStepBytes, PROT_NONE,
                      MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    if (at == MAP_FAILED) return;
    auto* bytes = static_cast<char*>(at);
    const auto address = reinterpret_cast<std::uintptr_t>(bytes);
    const std::size_t skip = (kStepBytes - address % kStepBytes) % kStepBytes;
    // The unaligned ends go back.
    if (skip != 0) ::munmap(bytes, skip);
    if (kStepBytes - skip != 0) ::munmap(bytes + skip + kReservedBytes, kStepBytes - skip);
    reserved_ = bytes + skip;
    ::madvise(reserved_, kReservedBytes, MADV_HUGEPAGE);  // a request: usable either way
    data_ = reinterpret_cast<T*>(reserved_);
  }

  void freeHeapBlock() {
    if (data_ != nullptr && reserved_ == nullptr)
      ::operator delete (data_, std::align_val_t{alignof(T)});
  }

  void release() {
    if (reserved_ != nullptr)
      ::munmap(reserved_, kReservedBytes);
    else
      freeHeapBlock();
    reserved_ = nullptr, data_ = nullptr, size_ = 0, capacity_ = 0;
  }

  void take(GrowOnlyArray& other) {
    reserved_ = std::exchange(other.reserved_, nullptr);
    data_ = std::exchange(other.data_, nullptr);
    size_ = std::exchange(other.size_, 0);
    capacity_ = std::exchange(other.capacity_, 0);
  }

  char* reserved_ = nullptr;  // the reservation, or null: heap blocks
  T* data_ = nullptr;
  std::size_t size_ = 0;
  std::size_t capacity_ = 0;
};

}  // namespace cdb
