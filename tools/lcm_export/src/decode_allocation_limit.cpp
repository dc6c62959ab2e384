#include "headingd/lcm_export/decode_allocation_limit.hpp"

#include <cstdint>
#include <cstdlib>
#include <new>

namespace {
// No limit outside a DecodeAllocationLimit; per thread, trivially initialised (usable from
// operator new before anything else has run).
thread_local std::size_t allocation_limit = SIZE_MAX;
}  // namespace

// The replaceable global allocation functions ([new.delete.single]): malloc/free as the
// default ones, with the limit. operator new[] and the nothrow forms call these.
void* operator new(std::size_t size) {
  if (size > allocation_limit) throw std::bad_alloc();
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace headingd::lcm_export {

DecodeAllocationLimit::DecodeAllocationLimit(std::size_t max_bytes_per_allocation) : previous_(allocation_limit) {
  allocation_limit = max_bytes_per_allocation;
}

DecodeAllocationLimit::~DecodeAllocationLimit() { allocation_limit = previous_; }

}  // namespace headingd::lcm_export
