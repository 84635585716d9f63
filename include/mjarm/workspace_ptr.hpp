#pragma once
/// @file
/// `WorkspacePtr<T>`: a class's private workspace on the heap, copied with the class.
///
/// A class that holds an Eigen decomposition (LLT, LDLT, SelfAdjointEigenSolver, JacobiSVD, …)
/// by value makes every unit that includes its header parse and instantiate that module. With
/// the decomposition in a `struct Workspace` defined in the class's .cpp and held through a
/// `WorkspacePtr<Workspace>`, the public header needs only `Eigen/Core`. The workspace is
/// allocated once, in the constructor, so hot paths still allocate nothing.
///
/// The class declares its destructor and the copy and move operations it had in the header and
/// defines them `= default` in its .cpp, where `T` is complete (the members below are templates
/// instantiated there).

#include <memory>
#include <utility>

namespace mjarm {

/// Owns one `T` (or nothing, once moved from); copying copies the `T`.
template <class T>
class WorkspacePtr {
 public:
  WorkspacePtr() noexcept = default;
  /// Takes ownership of @p p.
  explicit WorkspacePtr(std::unique_ptr<T> p) noexcept : p_(std::move(p)) {}

  WorkspacePtr(const WorkspacePtr& other)
      : p_(other.p_ ? std::make_unique<T>(*other.p_) : nullptr) {}
  /// Copies into the existing `T` when there is one (reusing its storage).
  WorkspacePtr& operator=(const WorkspacePtr& other) {
    if (this == &other) return *this;
    if (!other.p_) {
      p_.reset();
    } else if (p_) {
      *p_ = *other.p_;
    } else {
      p_ = std::make_unique<T>(*other.p_);
    }
    return *this;
  }
  WorkspacePtr(WorkspacePtr&&) noexcept = default;
  WorkspacePtr& operator=(WorkspacePtr&&) noexcept = default;
  ~WorkspacePtr() = default;

  // const reaches the T as const: a const method of the owner cannot change its workspace
  // (except its `mutable` members, the caches)
  T& operator*() noexcept { return *p_; }
  const T& operator*() const noexcept { return *p_; }
  T* operator->() noexcept { return p_.get(); }
  const T* operator->() const noexcept { return p_.get(); }

 private:
  std::unique_ptr<T> p_;
};

/// A `WorkspacePtr` holding `T(args...)`.
template <class T, class... Args>
WorkspacePtr<T> make_workspace(Args&&... args) {
  return WorkspacePtr<T>(std::make_unique<T>(std::forward<Args>(args)...));
}

}  // namespace mjarm
