// Recycles large heap blocks across fuzz inputs, for targets that build an
// object with a large table on every input (topdump's Analyzer allocates a
// 373 KB identifier table and clears it). ASan serves blocks above 128 KiB
// with a fresh mmap and unmaps them on free, so every input pays a page
// fault per 4 KiB touched: on the shared build VM that was 6 ms of the
// capture and TCP targets' 7 ms per input (page faults cost ~65 us there).
//
// This header replaces the global operator new/delete (all forms) with ones
// that allocate through malloc/free, which ASan intercepts: heap overflows,
// use-after-free and leaks are found as before. A freed block above 128 KiB
// is kept instead, poisoned (any access is an ASan "use-after-poison"
// report), and handed out again to an allocation of exactly its size made
// while a later input runs (never the input that freed it, so a dangling
// pointer is caught within the input, as with ASan's quarantine). The first
// 4 KiB of a reused block are filled with 0xBE, as ASan fills new blocks.
// What is lost: ASan's new/delete[] mismatch report (every form goes to
// malloc/free).
//
// Include in exactly one translation unit of a target, and call
// topfuzz::big_blocks_next_input() at the start of LLVMFuzzerTestOneInput.
// Only in libFuzzer builds: the replay build keeps ASan's own operators.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <new>

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define TOPKIT_FUZZ_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define TOPKIT_FUZZ_ASAN 1
#endif
#ifdef TOPKIT_FUZZ_ASAN
#include <sanitizer/asan_interface.h>
#endif

namespace topfuzz {

#ifdef TOPKIT_LIBFUZZER
namespace big_blocks_detail {

constexpr std::size_t kBig = std::size_t{128} << 10;  // ASan's largest size class
constexpr int kSlots = 16;

struct Slot {
  void* p = nullptr;
  std::size_t n = 0;
  bool in_use = false;
  std::uint64_t freed_in = 0;  // input number when freed
};

struct State {
  std::mutex m;
  Slot slots[kSlots];
  std::uint64_t input = 1;
};

inline State& state() {
  static State* s = new (std::malloc(sizeof(State))) State;  // never freed
  return *s;
}

// Marks [p, p + n) unaddressable (poisoned) or addressable again, for ASan.
inline void set_poisoned(void* p, std::size_t n, bool poisoned) {
#ifdef TOPKIT_FUZZ_ASAN
  if (poisoned)
    ASAN_POISON_MEMORY_REGION(p, n);
  else
    ASAN_UNPOISON_MEMORY_REGION(p, n);
#else
  (void)p, (void)n, (void)poisoned;
#endif
}

inline void* allocate(std::size_t n, std::size_t align) {
  if (n == 0) n = 1;
  if (n > kBig && align <= alignof(std::max_align_t)) {
    State& s = state();
    std::lock_guard<std::mutex> lock(s.m);
    for (Slot& x : s.slots) {
      if (x.p != nullptr && !x.in_use && x.n == n && x.freed_in < s.input) {
        x.in_use = true;
        set_poisoned(x.p, n, false);
        std::memset(x.p, 0xBE, n < 4096 ? n : 4096);
        return x.p;
      }
    }
    void* p = std::malloc(n);
    if (p == nullptr) return nullptr;
    for (Slot& x : s.slots) {
      if (x.p == nullptr) {
        x = Slot{p, n, true, 0};
        break;
      }
    }
    return p;
  }
  if (align <= alignof(std::max_align_t)) return std::malloc(n);
  void* p = nullptr;
  return posix_memalign(&p, align, n) == 0 ? p : nullptr;
}

inline void release(void* p) {
  if (p == nullptr) return;
  State& s = state();
  {
    std::lock_guard<std::mutex> lock(s.m);
    for (Slot& x : s.slots) {
      if (x.p != p) continue;
      if (!x.in_use) {
        std::fprintf(stderr, "==big_blocks: attempting double-free of %p (%zu bytes)\n", p, x.n);
        std::abort();
      }
      x.in_use = false;
      x.freed_in = s.input;
      set_poisoned(p, x.n, true);
      return;
    }
  }
  std::free(p);
}

}  // namespace big_blocks_detail

inline void big_blocks_next_input() {
  auto& s = big_blocks_detail::state();
  std::lock_guard<std::mutex> lock(s.m);
  ++s.input;
}
#else
inline void big_blocks_next_input() {}
#endif

}  // namespace topfuzz

#ifdef TOPKIT_LIBFUZZER
// clang-format off
void* operator new(std::size_t n) {
  void* p = topfuzz::big_blocks_detail::allocate(n, 0);
  if (p == nullptr) throw std::bad_alloc();
  return p;
}
void* operator new[](std::size_t n) { return ::operator new(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept { return topfuzz::big_blocks_detail::allocate(n, 0); }
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept { return topfuzz::big_blocks_detail::allocate(n, 0); }
void* operator new(std::size_t n, std::align_val_t a) {
  void* p = topfuzz::big_blocks_detail::allocate(n, static_cast<std::size_t>(a));
  if (p == nullptr) throw std::bad_alloc();
  return p;
}
void* operator new[](std::size_t n, std::align_val_t a) { return ::operator new(n, a); }
void* operator new(std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept { return topfuzz::big_blocks_detail::allocate(n, static_cast<std::size_t>(a)); }
void* operator new[](std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept { return topfuzz::big_blocks_detail::allocate(n, static_cast<std::size_t>(a)); }
void operator delete(void* p) noexcept { topfuzz::big_blocks_detail::release(p); }
void operator delete[](void* p) noexcept { topfuzz::big_blocks_detail::release(p); }
void operator delete(void* p, std::size_t) noexcept { topfuzz::big_blocks_detail::release(p); }
void operator delete[](void* p, std::size_t) noexcept { topfuzz::big_blocks_detail::release(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { topfuzz::big_blocks_detail::release(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { topfuzz::big_blocks_detail::release(p); }
void operator delete(void* p, std::align_val_t) noexcept { topfuzz::big_blocks_detail::release(p); }
void operator delete[](void* p, std::align_val_t) noexcept { topfuzz::big_blocks_detail::release(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { topfuzz::big_blocks_detail::release(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { topfuzz::big_blocks_detail::release(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { topfuzz::big_blocks_detail::release(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { topfuzz::big_blocks_detail::release(p); }
// clang-format on
#endif
