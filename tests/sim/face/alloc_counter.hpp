// Counts global operator new calls while armed; the replacement operators live in
// alloc_counter.cpp so every test in the binary shares them.
#pragma once

namespace facectl::face::testing {

void arm_alloc_counter();
long disarm_alloc_counter();  // returns the allocations seen while armed

}  // namespace facectl::face::testing
