// Global operator new and delete replaced in a test binary that watches its
// heap allocations: include this in the binary's one source file, which
// defines observeAllocation. (Eigen's dense storage comes from malloc,
// which this does not see.)
#pragma once

#include <cstdlib>
#include <new>

// Told the size of every allocation operator new makes.
void observeAllocation(std::size_t size);

void* operator new(std::size_t size) {
  observeAllocation(size);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
