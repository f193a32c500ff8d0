#pragma once

namespace facectl::testing {

// Counts heap allocations (malloc, calloc, realloc, memalign, aligned_alloc,
// posix_memalign; operator new ends up in malloc) made by the calling thread
// between begin and end. allocation_counter.cpp interposes the C allocator
// for the whole process, so it is compiled into the test binary itself.
void begin_counting_allocations();
long end_counting_allocations();

}  // namespace facectl::testing
