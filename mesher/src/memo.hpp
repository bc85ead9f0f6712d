// Private: answers remembered by the bytes of their problem, shared by threads. The re-fill's
// cavities (CavityMemo, cavity.cpp) and the faces of mesh_part's attempts (FaceFillMemo,
// fill.cpp) use it: a problem that reads nothing but those bytes gets the same answer, to the
// bit, wherever and whenever it comes again.
#pragma once

#include <cstddef>
#include <memory>
#include <mutex>
#include <string>
#include <type_traits>
#include <unordered_map>
#include <utility>
#include <vector>

namespace laytracks::mesher_detail {

/// Appends the bytes of a trivially copyable value to a memo key.
template <class T>
void append_bytes(std::string& key, const T& value) {
  static_assert(std::is_trivially_copyable_v<T>);
  key.append(reinterpret_cast<const char*>(&value), sizeof value);
}

/// Appends the bytes of a vector's elements (not its size) to a memo key.
template <class T>
void append_bytes(std::string& key, const std::vector<T>& values) {
  static_assert(std::is_trivially_copyable_v<T>);
  key.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

template <class Answer>
class LockedMemo {
 public:
  /// Holds at most about `max_bytes` of keys and answers (as the callers count them); past
  /// that it only stops growing, and answers not held are computed again.
  explicit LockedMemo(std::size_t max_bytes) : max_bytes_(max_bytes) {}

  /// The answer remembered for `key`, else null.
  std::shared_ptr<const Answer> find(const std::string& key) const {
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto it = answers_.find(key);
    return it == answers_.end() ? nullptr : it->second;
  }

  /// Remembers `answer` (of `bytes`, key included) for `key`, unless the memo is full. Two
  /// threads that computed one problem at once insert the same answer: the first stays.
  void insert(std::string key, std::shared_ptr<const Answer> answer, std::size_t bytes) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (bytes_ > max_bytes_) return;
    bytes_ += bytes;
    answers_.emplace(std::move(key), std::move(answer));
  }

 private:
  const std::size_t max_bytes_;
  mutable std::mutex mutex_;
  std::unordered_map<std::string, std::shared_ptr<const Answer>> answers_;
  std::size_t bytes_ = 0;
};

}  // namespace laytracks::mesher_detail
