#pragma once
// Counts heap allocations, to prove a hot path allocates nothing.
//
// Linking the ftsense::testing library replaces the global operator new (all forms) with a
// counting version that forwards to malloc. Use:
//
//   ftsense::testing::AllocationScope scope;
//   for (...) pipeline.step(t);
//   EXPECT_EQ(scope.allocations(), 0u);

#include <cstddef>

namespace ftsense::testing {

// Number of operator new calls in this process so far (all threads).
[[nodiscard]] std::size_t allocation_count() noexcept;

class AllocationScope {
 public:
  AllocationScope() noexcept : start_(allocation_count()) {}
  [[nodiscard]] std::size_t allocations() const noexcept { return allocation_count() - start_; }

 private:
  std::size_t start_;
};

}  // namespace ftsense::testing
