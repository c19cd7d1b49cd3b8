// A FIFO of reusable slots: the stream decoder's ready items, topdump's
// pending requests.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

namespace top::detail {

// A FIFO that keeps its slots, and the buffers of their strings, for reuse:
// items and requests come and go all the time, and a std::deque allocates
// and frees a block every few of them. Elements are reached by age, oldest
// first.
template <class T>
class Ring {
 public:
  std::size_t size() const noexcept { return n_; }
  bool empty() const noexcept { return n_ == 0; }
  T& operator[](std::size_t i) noexcept { return v_[(head_ + i) & (v_.size() - 1)]; }
  const T& operator[](std::size_t i) const noexcept { return v_[(head_ + i) & (v_.size() - 1)]; }
  T& front() noexcept { return (*this)[0]; }
  // A slot at the back, as an earlier element left it: the caller assigns
  // every member.
  T& push_back() {
    if (n_ == v_.size()) grow();
    ++n_;
    return (*this)[n_ - 1];
  }
  void pop_front() noexcept {
    head_ = (head_ + 1) & (v_.size() - 1);
    --n_;
  }
  // Empties it; the slots stay.
  void clear() noexcept { head_ = n_ = 0; }
  // When empty, keeps only `keep` slots (a power of two): a burst's slots
  // are not held forever.
  void trim(std::size_t keep) {
    if (n_ != 0 || v_.size() <= keep) return;
    v_.resize(keep);
    v_.shrink_to_fit();
    head_ = 0;
  }
  // Removes element i; the later ones move down by one, and its slot (with
  // its buffers) goes to the back for reuse: one move per later element.
  void erase(std::size_t i) noexcept {
    if (i + 1 == n_) {  // the newest (most replies answer it): nothing moves
      --n_;
      return;
    }
    T gone = std::move((*this)[i]);
    for (; i + 1 < n_; ++i) (*this)[i] = std::move((*this)[i + 1]);
    (*this)[n_ - 1] = std::move(gone);
    --n_;
  }

 private:
  void grow() {
    std::vector<T> bigger(v_.empty() ? 8 : v_.size() * 2);  // a power of two
    for (std::size_t i = 0; i < n_; ++i) bigger[i] = std::move((*this)[i]);
    v_ = std::move(bigger);
    head_ = 0;
  }
  std::vector<T> v_;
  std::size_t head_ = 0, n_ = 0;
};

}  // namespace top::detail
